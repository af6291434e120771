#!/usr/bin/env bash
# Renders the demo (node + client + rviz) under Xvfb and saves a screenshot of rviz showing the
# solved default scene: tools/screenshot_rviz.sh [output.png] [seconds after the solve] [launch]
# [client arguments] [rviz config] [command after the solve] (defaults docs/rviz_default_scene.png, 5, demo.launch, none,
# the launch's; robot_demo.launch shows the planar arm; e.g. "--obstacle 0 6 0.8" puts a post on
# the push line; "--push-t -0.99 0.42 -2.98 2.03 -0.97" with config/push_t.rviz shows Push-T). The playback loops every 6 s (5 s of motion at
# ~playback_rate 1, then 1 s pause): 8.5 s after the solve it shows t ~ 2.5 s, mid-push.
# A command after the solve (e.g. "rosrun fesd_trajopt drag_target.py object 0.4 7.0", a dragged
# target) runs before the delay.
# Needs a built workspace (tools/run_default.sh) and imagemagick for `import`.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
source_workspace
OUTPUT="${1:-$REPO_DIR/docs/rviz_default_scene.png}"
DELAY="${2:-5}"
LAUNCH_FILE="${3:-demo.launch}"
CLIENT_ARGS="${4:-}"
RVIZ_CONFIG="${5:-}"
AFTER_SOLVE="${6:-}"
DISPLAY_NUMBER=":$((90 + RANDOM % 9))"

Xvfb "$DISPLAY_NUMBER" -screen 0 1200x850x24 >/dev/null 2>&1 &
XVFB_PID=$!
LOG="$(mktemp)"
cleanup() {
  [ -n "${LAUNCH_PID:-}" ] && kill "$LAUNCH_PID" 2>/dev/null && wait "$LAUNCH_PID" 2>/dev/null
  kill "$XVFB_PID" 2>/dev/null
  rm -f "$LOG"
}
trap cleanup EXIT
sleep 2

LAUNCH_ARGS=()
[ -n "$CLIENT_ARGS" ] && LAUNCH_ARGS+=("client_args:=$CLIENT_ARGS")
[ -n "$RVIZ_CONFIG" ] && LAUNCH_ARGS+=("rviz_config:=$RVIZ_CONFIG")
DISPLAY="$DISPLAY_NUMBER" roslaunch fesd_trajopt "$LAUNCH_FILE" "${LAUNCH_ARGS[@]}" >"$LOG" 2>&1 &
LAUNCH_PID=$!
# The client prints the round trip last; then give rviz a few frames to draw the markers.
for _ in $(seq 300); do
  grep -q "round trip" "$LOG" && break
  sleep 1
done
grep -q "round trip" "$LOG" || { cat "$LOG"; echo "no solution within 300 s" >&2; exit 1; }
[ -z "$AFTER_SOLVE" ] || DISPLAY="$DISPLAY_NUMBER" bash -c "$AFTER_SOLVE"
sleep "$DELAY"
DISPLAY="$DISPLAY_NUMBER" import -window root "$OUTPUT"
grep -A20 "fesd_trajopt.*demo:" "$LOG" | grep -v "^\[" || true
echo "== screenshot: $OUTPUT"
