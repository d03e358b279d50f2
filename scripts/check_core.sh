#!/usr/bin/env bash
# The core library and its unit tests built alone (test/standalone: no catkin, no ROS) with
# AddressSanitizer + UndefinedBehaviorSanitizer (its value checks; its pointer checks are ASan's
# here: test/standalone/CMakeLists.txt), then every unit test and every fuzz target's replay
# of its seed corpus and regression inputs (test/fuzz) run under them. Any sanitizer report fails
# the test that caused it. Ends with `sanitizers: N passed, M failed`; exits non-zero on a failure.
# Part of scripts/run_tests.sh. Build in .ws/sanitize (git-ignored).
# Usage: scripts/check_core.sh [build|test]   (~6.5 minutes on two cores from scratch: 5 to build, 1.5 to test)
#   build: only build the tree; test: only run the tests of a built tree; no argument: both.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
BUILD="$AP_WS/sanitize"
JOBS="${AP_JOBS:-$(nproc)}"
PHASE="${1:-all}"
case "$PHASE" in all|build|test) ;; *) echo "check_core.sh: unknown phase '$PHASE' (build, test or none)"; exit 2 ;; esac
# clang: it compiles this tree with both sanitizers in half gcc's time, and a second compiler
# checks that nothing depends on gcc's choices (the simulators draw their random numbers one per
# statement, so a seed makes the same scene under both). CXX chooses another compiler.
COMPILER="${CXX:-$(command -v clang++)}"
if [ "$PHASE" != test ] && [ -f "$BUILD/CMakeCache.txt" ] &&
   ! grep -q "^CMAKE_CXX_COMPILER:[A-Z]*=$COMPILER\$" "$BUILD/CMakeCache.txt"; then
  rm -rf "$BUILD"  # configured with another compiler
fi
mkdir -p "$BUILD"
log="$BUILD/build.log"
if [ "$PHASE" != test ] && ! { cmake -S "$AP_ROOT/test/standalone" -B "$BUILD" -DCMAKE_BUILD_TYPE=None -DAP_SANITIZE=ON -DCMAKE_CXX_COMPILER="$COMPILER" &&
       cmake --build "$BUILD" -j"$JOBS"; } > "$log" 2>&1; then
  tail -n 40 "$log"; echo "check_core: sanitizer build FAILED (log: $log)"
  echo "sanitizers: 0 passed, 1 failed"; exit 1
fi
if [ "$PHASE" = build ]; then echo "check_core: sanitizer tree built in $BUILD"; exit 0; fi
if [ ! -f "$BUILD/CTestTestfile.cmake" ]; then
  echo "check_core: no sanitizer tree in $BUILD (run scripts/check_core.sh build first)"
  echo "sanitizers: 0 passed, 1 failed"; exit 1
fi
# Leaks count as failures; a report stops the process (halt_on_error) with a stack trace.
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:abort_on_error=0:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# One ctest test a program; the gtest cases are counted from each program's XML
# (summarize_test_results.py --programs: a program that died outside its cases counts as a failure).
rm -rf "$BUILD/gtest_results" "$BUILD/programs.xml"
ctest --test-dir "$BUILD" -j"$JOBS" --output-on-failure --timeout 900 \
  --output-junit "$BUILD/programs.xml" > "$BUILD/ctest.log" 2>&1
summary="$(python3 "$AP_ROOT/scripts/summarize_test_results.py" "$BUILD/gtest_results" --programs "$BUILD/programs.xml")"
ok=$?
echo "$summary" | sed '$d'
[ "$ok" -ne 0 ] && echo "check_core: failures in $BUILD/ctest.log"
echo "$summary" | tail -n 1 | sed 's/^tests:/sanitizers:/'
[ "$ok" -eq 0 ]
