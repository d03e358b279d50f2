#!/usr/bin/env bash
# rostest helper for histogram_place_recognizer_route.test: a reference drive through the indoor
# building (cloudy, seed 1, 1 Hz, 160 x 120) becomes a route database (train_places --route: every
# image its own place), histogram_place_recognizer starts on it, and another drive along the same
# route (cloudy, seed 2: other light levels, odometry and camera noise) is played: its first 150 s,
# then (a kidnap) from 300 s on for 150 s. Each part is announced on /test_phase (std_msgs/String:
# test, kidnap, done). Fixed seeds: the same bags every run, made here rather than committed.
# Usage (as a launch node): place_route_player.sh RATE [roslaunch's __name:= / __log:= args]
set -euo pipefail
RATE="${1:-10}"
OUT="$(mktemp -d)"
NODE=""
cleanup() { [ -n "$NODE" ] && kill "$NODE" 2> /dev/null; wait 2> /dev/null; rm -rf "$OUT"; }
trap cleanup EXIT
for run in reference:1 query:2; do
  rosrun adaptive_perception simulate_indoor --lighting cloudy --seed "${run#*:}" \
    --camera_rate_hz 1 --width_px 160 --height_px 120 --output "$OUT/${run%%:*}.bag" > /dev/null 2>&1
done
rosrun adaptive_perception train_places --bag "$OUT/reference.bag" --database "$OUT/route.sqlite" \
  --route > /dev/null 2>&1
rm -f "$OUT/reference.bag"
rosrun adaptive_perception histogram_place_recognizer __name:=histogram_place_recognizer \
  _database:="$OUT/route.sqlite" _max_rate_hz:=100 > "$OUT/node.log" 2>&1 &
NODE=$!
sleep 5
rostopic pub -1 /test_phase std_msgs/String "data: 'test'" > /dev/null
rosbag play --quiet --rate "$RATE" --duration 150 "$OUT/query.bag"
sleep 2
rostopic pub -1 /test_phase std_msgs/String "data: 'kidnap'" > /dev/null
rosbag play --quiet --rate "$RATE" --start 300 --duration 150 "$OUT/query.bag"
sleep 3
rostopic pub -1 /test_phase std_msgs/String "data: 'done'" > /dev/null
