#!/usr/bin/env bash
# README command 2 (after tools/install_dependencies.sh): checks the formatting, builds (Release,
# warnings as errors) and runs every test (gtest units, rostests), then installs the package and
# runs the demo from the install space; exits non-zero on any failure.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
"$REPO_DIR/tools/check_format.sh"
build_workspace -DFESD_WERROR=ON
source_workspace
cd "$WS_DIR"
rm -rf build/test_results
catkin_make run_tests -j2
catkin_test_results build/test_results --verbose
echo "== the install space"
catkin_make install -j2 >/dev/null
(source_workspace install && run_demo >/dev/null && echo "demo from the install space: SUCCESS")
