#!/usr/bin/env bash
# rostest helper for histogram_place_recognizer_sim.test: simulates the training bag (cloudy, seed 1)
# and the test bag (cloudy, seed 2) of the indoor building at 1 Hz, 160 x 120 (fixed seeds, so the
# same bags every run; ~30 MB each, so they are made here rather than committed), then announces
# each phase on /test_phase (std_msgs/String: train, test, done) and plays the bag.
# Usage (as a launch node): place_test_player.sh RATE [roslaunch's __name:= / __log:= args]
set -euo pipefail
RATE="${1:-20}"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
for phase in train test; do
  seed=1; [ "$phase" = test ] && seed=2
  rosrun adaptive_perception simulate_indoor --lighting cloudy --seed "$seed" --camera_rate_hz 1 \
    --width_px 160 --height_px 120 --output "$OUT/$phase.bag" > /dev/null 2>&1
done
sleep 3
for phase in train test; do
  rostopic pub -1 /test_phase std_msgs/String "data: '$phase'" > /dev/null
  rosbag play --quiet --rate "$RATE" "$OUT/$phase.bag"
  sleep 2
done
rostopic pub -1 /test_phase std_msgs/String "data: 'done'" > /dev/null
