# Shared by the README's commands: installs what is missing, builds the catkin workspace, runs
# the demo.
# Sourced, not executed. The workspace lives beside the clone (<clone>_catkin_ws, outside git),
# not inside it: rosrun follows symlinks, and src/ links back to the clone.
set -euo pipefail

# ROS tools are Debian's and need Debian's python3, not one earlier on PATH (e.g. pyenv).
export PATH="/usr/bin:$PATH"
REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WS_DIR="${FESD_WS_DIR:-${REPO_DIR}_catkin_ws}"
ROS_PYTHON=/usr/bin/python3

DEBIAN_PACKAGES=(
  build-essential cmake pkg-config
  catkin libroscpp-dev ros-message-generation librostest-dev python3-rostest python3-roslaunch
  libactionlib-dev libactionlib-msgs-dev ros-actionlib-msgs python3-actionlib python3-actionlib-msgs
  rosbash libinteractive-markers-dev libvisualization-msgs-dev libgeometry-msgs-dev libnav-msgs-dev libtf2-ros-dev liburdfdom-dev libtinyxml2-dev rviz
  ros-std-msgs ros-geometry-msgs python3-rospy python3-std-msgs python3-geometry-msgs
  python3-visualization-msgs python3-nav-msgs python3-tf2-ros python3-rosservice python3-rostopic python3-rosnode
  coinor-libipopt-dev coinor-libcbc-dev coinor-libclp-dev libsuitesparse-dev libmetis-dev libeigen3-dev
  libgtest-dev libsiconos-kernel-dev
  liborocos-kdl-dev libkdl-parser-dev libtrajectory-msgs-dev libsensor-msgs-dev python3-trajectory-msgs
  python3-sensor-msgs ros-robot-state-publisher ros-trajectory-msgs ros-sensor-msgs
  gnuplot-nox python3-matplotlib python3-numpy xvfb imagemagick clang-format
)

install_dependencies() {
  local missing=()
  for package in "${DEBIAN_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
      missing+=("$package")
  done
  if ((${#missing[@]})); then
    echo "== installing: ${missing[*]}"
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
  fi
}

build_workspace() {
  mkdir -p "$WS_DIR/src"
  ln -sfn "$REPO_DIR" "$WS_DIR/src/fesd_trajopt"
  echo "== building in $WS_DIR (Release)"
  (cd "$WS_DIR" && catkin_make -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE="$ROS_PYTHON" \
    -DCATKIN_ENABLE_TESTING=ON -j2 "$@")
}

# Sources the workspace's devel space, or the space given (e.g. install).
source_workspace() {
  set +u
  # shellcheck disable=SC1091
  source "$WS_DIR/${1:-devel}/setup.bash"
  set -u
}

# The main job, headless: the node (roslaunch, in the background) solves the default scene for the
# demo client (arguments go to it), which prints a summary and exits 0 only on SUCCESS; then the
# node is shut down.
# The client runs on its own rather than as a required node of demo.launch, whose end would make
# roslaunch report "REQUIRED process has died" after a successful demo.
run_demo() {
  local log
  log="$(mktemp)"
  roslaunch fesd_trajopt fesd_trajopt.launch >"$log" 2>&1 &
  local launch=$!
  for _ in $(seq 150); do  # the master first, or the client complains while it waits
    rosnode list >/dev/null 2>&1 && break
    sleep 0.2
  done
  local status=0
  rosrun fesd_trajopt demo_client.py "$@" || status=$?
  kill -INT "$launch" 2>/dev/null
  wait "$launch" 2>/dev/null || true
  if [ "$status" -ne 0 ]; then
    echo "== the demo FAILED (client exit code $status); the node's output:" >&2
    cat "$log" >&2
  fi
  rm -f "$log"
  return $status
}
