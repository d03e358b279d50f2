#!/usr/bin/env bash
# rostest helper for condensation_tracker_sim.test: simulates a tracking sequence (scenario $1,
# seed 1, $2 frames) as a bag, reads the target's first box from the same sequence written as a
# video + CSV, starts condensation_tracker with it as ~initial_roi, announces /test_phase (test,
# done) and plays the bag. Fixed seed: the same frames every run.
# Usage (as a launch node): tracking_test_player.sh SCENARIO FRAMES MODE [ENCODING] [roslaunch args]
# (ENCODING: of the bag's images, bgr8 by default, or rgb8 / mono8).
set -euo pipefail
SCENARIO="${1:-distractor}"
FRAMES="${2:-150}"
MODE="${3:-condensation}"
ENCODING=bgr8
case "${4:-}" in bgr8 | rgb8 | mono8) ENCODING="$4" ;; esac
OUT="$(mktemp -d)"
NODE=""
cleanup() { [ -n "$NODE" ] && kill "$NODE" 2> /dev/null; wait 2> /dev/null; rm -rf "$OUT"; }
trap cleanup EXIT
rosrun adaptive_perception simulate_tracking --scenario "$SCENARIO" --seed 1 --frames "$FRAMES" \
  --output "$OUT/seq.bag" --encoding "$ENCODING" > /dev/null 2>&1
rosrun adaptive_perception simulate_tracking --scenario "$SCENARIO" --seed 1 --frames 1 \
  --video "$OUT/first.avi" > /dev/null 2>&1
ROI="[$(sed -n 2p "$OUT/first.csv" | cut -d, -f2-5)]"
rosrun adaptive_perception condensation_tracker __name:=condensation_tracker _mode:="$MODE" \
  _initial_roi:="$ROI" _max_rate_hz:=1000 > "$OUT/node.log" 2>&1 &
NODE=$!
sleep 3
rostopic pub -1 /test_phase std_msgs/String "data: 'test'" > /dev/null
# In step with the tracker (src/tools/lockstep_player.cpp): each frame waits for the tracked object
# of the one before, so the test checks tracking, not how many frames a loaded machine lets the
# node keep up with (at half speed it answered 119 of 149 frames beside two other tests).
rosrun adaptive_perception lockstep_player "$OUT/seq.bag" _trigger_topic:=camera/image_raw \
  _output_topic:=tracked_object _delay_s:=2 > /dev/null
sleep 2
rostopic pub -1 /test_phase std_msgs/String "data: 'done'" > /dev/null
