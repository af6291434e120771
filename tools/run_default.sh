#!/usr/bin/env bash
# README command 1 (after tools/install_dependencies.sh): builds (Release) and runs the main job
# on the shipped default: the demo, headless. The node solves the default scene (collaborative
# manipulation) for the demo client, which prints a summary; exits non-zero unless SUCCESS.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
build_workspace
source_workspace
run_demo
