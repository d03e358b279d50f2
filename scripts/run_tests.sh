#!/usr/bin/env bash
# Sets up (apt + build), then runs every test and ends with one line `tests: N passed, M failed`:
#   - the ROS tests (rostests, launch-file checks, parameters_documented_test) from the catkin
#     build, three at a time (AP_TEST_JOBS): most of them wait on bags played in real time, and no
#     two share a master (rostest starts each on a free port);
#   - the install check (scripts/check_install.sh);
#   - the core's unit tests and the fuzz targets' corpus replays, built alone with AddressSanitizer
#     + UndefinedBehaviorSanitizer (scripts/check_core.sh). That tree builds and then runs its tests
#     at the lowest CPU priority beside the catkin build and the ROS tests; the unit tests run there
#     only, not a second time from the catkin build (`catkin_make run_tests` still runs them all, as
#     catkin users expect).
# N counts the catkin test cases, the install check, and the sanitizer run's gtest cases and fuzz
# replays. Prints the time of each stage. Exits non-zero when any test failed or did not run.
# The verdict comes from the result XML files (ctest and catkin's run_tests exit 0 on some failures).
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
stage() { echo "run_tests: $1 after $(( SECONDS / 60 )) min $(( SECONDS % 60 )) s"; }
"$AP_ROOT/scripts/setup.sh" --no-build || { echo "tests: 0 passed, 1 failed"; exit 1; }
mkdir -p "$AP_WS"
rm -f "$AP_WS/check_core_built_at" "$AP_WS/check_core_tested_at"
# The sanitizer tree, built and then tested beside everything below at nice 19: it takes only the
# CPU that the catkin build and the ROS tests leave idle. Each half's end time goes to a file. It
# stays in this session: a new one (setsid) is a scheduler group of its own, where nice has no effect
# on the build beside it.
(
  nice -n 19 "$AP_ROOT/scripts/check_core.sh" build > "$AP_WS/check_core_build.log" 2>&1 || exit 1
  echo "$SECONDS" > "$AP_WS/check_core_built_at"
  nice -n 19 "$AP_ROOT/scripts/check_core.sh" test > "$AP_WS/check_core.log" 2>&1
  echo "$SECONDS" > "$AP_WS/check_core_tested_at"
) &
san_job=$!
# Stops the job and everything it started (the compilers too), children first.
kill_tree() { local c; for c in $(pgrep -P "$1"); do kill_tree "$c"; done; kill "$1" 2> /dev/null; }
stop_sanitizer() { kill_tree "$san_job"; }
"$AP_ROOT/scripts/setup.sh" || { stop_sanitizer; echo "tests: 0 passed, 1 failed"; exit 1; }
stage "setup (apt, catkin build) done"
cd "$AP_WS"
set +u; source devel/setup.bash; set -u
export ROS_HOME="$AP_WS/ros_home" ROS_LOG_DIR="$AP_WS/ros_home/log"
results="$AP_WS/build/test_results"
rm -rf "$results"
JOBS="${AP_JOBS:-$(nproc)}"
TEST_JOBS="${AP_TEST_JOBS:-3}"
if ! catkin_make -j"$JOBS" ros_tests > "$AP_WS/tests_build.log" 2>&1; then
  tail -n 60 "$AP_WS/tests_build.log"; echo "test build FAILED (log: $AP_WS/tests_build.log)"
  stop_sanitizer
  echo "tests: 0 passed, 1 failed"; exit 1
fi
stage "test build done"
( cd "$AP_WS/build" && ctest -LE core_unit -j"$TEST_JOBS" --timeout 900 ) > "$AP_WS/run_tests.log" 2>&1
grep -E '^ *[0-9]+/[0-9]+ Test' "$AP_WS/run_tests.log" | sed -E 's/_ctest_adaptive_perception_//; s/ \.{3,}/ /' || true
stage "catkin tests done"
summary="$(python3 "$AP_ROOT/scripts/summarize_test_results.py" "$results")"
echo "$summary" | sed '$d'
catkin_line="$(echo "$summary" | tail -n 1)"
echo "catkin $catkin_line"
# The install space as a downstream package sees it.
install_ok=1
"$AP_ROOT/scripts/check_install.sh" || install_ok=0
stage "install check done"
at() { local t; t="$(cat "$1")"; echo "after $(( t / 60 )) min $(( t % 60 )) s"; }
wait "$san_job"
if [ -f "$AP_WS/check_core_built_at" ]; then
  echo "run_tests: sanitizer build (background) done $(at "$AP_WS/check_core_built_at")"
  cat "$AP_WS/check_core.log"
  [ -f "$AP_WS/check_core_tested_at" ] &&
    echo "run_tests: sanitizer tests (background) done $(at "$AP_WS/check_core_tested_at")"
  san_line="$(tail -n 1 "$AP_WS/check_core.log")"
else
  cat "$AP_WS/check_core_build.log"
  san_line="sanitizers: 0 passed, 1 failed"
fi
stage "all done"
num() { echo "$1" | sed -n "s/.* \([0-9]*\) $2.*/\1/p"; }
p1=$(num "$catkin_line" passed); f1=$(num "$catkin_line" failed)
p2=$(num "$san_line" passed); f2=$(num "$san_line" failed)
p=$(( ${p1:-0} + ${p2:-0} + install_ok )); f=$(( ${f1:-0} + ${f2:-0} + 1 - install_ok ))
[ -z "$p1" ] || [ -z "$p2" ] && f=$((f + 1))  # a part that printed no verdict counts as a failure
echo "tests: $p passed, $f failed"
[ "$f" -eq 0 ] && [ "$p" -gt 0 ]
