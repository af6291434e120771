#!/usr/bin/env bash
# README command 2: installs what is missing, builds (Release) and runs every test (gtest units,
# rostests); exits non-zero on any failure.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_dependencies
build_workspace
source_workspace
cd "$WS_DIR"
rm -rf build/test_results
catkin_make run_tests -j2
catkin_test_results build/test_results --verbose
