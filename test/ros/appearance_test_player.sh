#!/usr/bin/env bash
# rostest helper for appearance_localizer_sim.test: simulates a training run of the indoor building
# (cloudy, seed 1, 1 Hz) and builds its SIFT database with train_places --features, simulates part
# of another run (cloudy, seed 2, the first 240 s), starts appearance_localizer on the database,
# announces /test_phase (test, done) and plays the test bag. Fixed seeds: the same data every run.
# Usage (as a launch node): appearance_test_player.sh RATE [roslaunch's __name:= / __log:= args]
set -euo pipefail
RATE="${1:-5}"
OUT="$(mktemp -d)"
NODE=""
cleanup() { [ -n "$NODE" ] && kill "$NODE" 2> /dev/null; wait 2> /dev/null; rm -rf "$OUT"; }
trap cleanup EXIT
rosrun adaptive_perception simulate_indoor --lighting cloudy --seed 1 --camera_rate_hz 1 \
  --output "$OUT/train.bag" > /dev/null 2>&1
rosrun adaptive_perception train_places --bag "$OUT/train.bag" --database "$OUT/db.sqlite" \
  --images_per_place 0 --features --spaces hsv > /dev/null 2>&1
rm -f "$OUT/train.bag"
rosrun adaptive_perception simulate_indoor --lighting cloudy --seed 2 --camera_rate_hz 1 \
  --duration_s 240 --output "$OUT/test.bag" > /dev/null 2>&1
rosrun adaptive_perception appearance_localizer __name:=appearance_localizer \
  _database:="$OUT/db.sqlite" _max_rate_hz:=100 > "$OUT/node.log" 2>&1 &
NODE=$!
sleep 5
rostopic pub -1 /test_phase std_msgs/String "data: 'test'" > /dev/null
rosbag play --quiet --rate "$RATE" "$OUT/test.bag"
sleep 3
rostopic pub -1 /test_phase std_msgs/String "data: 'done'" > /dev/null
