#!/usr/bin/env bash
# README command 1: installs what is missing, builds (Release) and runs the main job on the
# shipped default: the demo, headless. The node solves the default scene (collaborative
# manipulation) for the demo client, which prints a summary; exits non-zero unless SUCCESS.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_dependencies
build_workspace
source_workspace
LOG="$(mktemp)"
trap 'rm -f "$LOG"' EXIT
roslaunch fesd_trajopt demo.launch rviz:=false 2>&1 | tee "$LOG"
# roslaunch does not pass on the client's exit code; its summary line carries the status.
grep -q "^fesd_trajopt demo: SUCCESS" "$LOG"
