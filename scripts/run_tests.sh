#!/usr/bin/env bash
# Sets up (apt + build), builds and runs every gtest and rostest, and ends with one line
# `tests: N passed, M failed`. Exits non-zero when any test failed or did not run.
# catkin_make run_tests itself exits 0 on failures, so the verdict comes from the result XML files.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
"$AP_ROOT/scripts/setup.sh" || { echo "tests: 0 passed, 1 failed"; exit 1; }
cd "$AP_WS"
set +u; source devel/setup.bash; set -u
export ROS_HOME="$AP_WS/ros_home" ROS_LOG_DIR="$AP_WS/ros_home/log"
results="$AP_WS/build/test_results"
rm -rf "$results"
JOBS="${AP_JOBS:-$(nproc)}"
if ! catkin_make -j"$JOBS" tests > "$AP_WS/tests_build.log" 2>&1; then
  tail -n 60 "$AP_WS/tests_build.log"; echo "test build FAILED (log: $AP_WS/tests_build.log)"
  echo "tests: 0 passed, 1 failed"; exit 1
fi
catkin_make -j1 run_tests 2>&1 | tee "$AP_WS/run_tests.log" | \
  grep -E '^\[ *(RUN|  +OK|  FAILED|  PASSED) |^\[ROSTEST\]|^ *\[(passed|FAILURE|ERROR)\]|^-- run_tests' || true
python3 "$AP_ROOT/scripts/summarize_test_results.py" "$results"
