#!/usr/bin/env bash
# Starts the node on the default configuration and runs bench/node_roundtrip.py against it:
# bench/node_roundtrip.sh [--cases=a,b] [--repeat=N]. Needs a built workspace.
source "$(dirname "${BASH_SOURCE[0]}")/../tools/common.sh"
source_workspace
roslaunch fesd_trajopt fesd_trajopt.launch >/dev/null 2>&1 &
LAUNCH_PID=$!
trap 'kill "$LAUNCH_PID" 2>/dev/null; wait "$LAUNCH_PID" 2>/dev/null' EXIT
"$ROS_PYTHON" "$REPO_DIR/bench/node_roundtrip.py" "$@"
