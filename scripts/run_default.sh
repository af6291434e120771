#!/usr/bin/env bash
# README command 1: installs what is missing, builds (Release) and runs the main job on the
# shipped default: seed 000 Example 1 simulated with the FESD integrator.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_dependencies
build_workspace
source_workspace
rosrun fesd_trajopt fesd_circle_example
