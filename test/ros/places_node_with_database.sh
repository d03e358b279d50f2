#!/usr/bin/env bash
# For hostile_histogram_place_recognizer.test and hostile_appearance_localizer.test: makes the data a
# place node needs, then BECOMES the node (exec), so roslaunch runs and stops it as usual.
#   DIR/db.sqlite  train_places on a simulated training run of the indoor building (cloudy, seed 1)
#   DIR/test.bag   another run (cloudy, seed 2, the first DURATION_S seconds), written last and
#                  renamed into place, so a test waiting for it finds it whole
# Both at 1 Hz and WIDTHxHEIGHT pixels. Fixed seeds: the same data every run. Usage (as a launch node):
#   places_node_with_database.sh DIR NODE DURATION_S WIDTHxHEIGHT TRAIN_ARGS... -- NODE_ARGS... [roslaunch args]
set -euo pipefail
DIR="$1" NODE="$2" DURATION="$3" SIZE="$4"
shift 4
TRAIN=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do TRAIN+=("$1"); shift; done
[ $# -gt 0 ] && shift
mkdir -p "$DIR"
SIM=(--lighting cloudy --camera_rate_hz 1 --width_px "${SIZE%x*}" --height_px "${SIZE#*x}")
rosrun adaptive_perception simulate_indoor "${SIM[@]}" --seed 1 --output "$DIR/train.bag" > /dev/null 2>&1
rosrun adaptive_perception train_places --bag "$DIR/train.bag" --database "$DIR/db.sqlite" \
  "${TRAIN[@]}" > /dev/null 2>&1
rm -f "$DIR/train.bag"
rosrun adaptive_perception simulate_indoor "${SIM[@]}" --seed 2 --duration_s "$DURATION" \
  --output "$DIR/test.tmp.bag" > /dev/null 2>&1
mv "$DIR/test.tmp.bag" "$DIR/test.bag"
exec rosrun adaptive_perception "$NODE" _database:="$DIR/db.sqlite" "$@"
