#!/usr/bin/env bash
# Reproduces the place-recognition experiments of papers/004 in the indoor simulator:
#  1. the paper's protocol: 11 places, 15 training and 15 test images each, the same lighting
#     (training run seed 1, test run seed 2, both cloudy): the tables of Tables 1-7 for every
#     test place, all 8 colour spaces and each distance;
#  2. across lighting: a database trained in each of night / cloudy / sunny, tested in each
#     (3 x 3), by the paper's protocol, single images, a sliding window and the Bayes filter.
# Writes results/places/<train>_<test>/ (results.yaml, images.csv, log.txt) and
# results/places/lighting.csv, and prints one line per pair:
#   places_lighting: train=L test=L accuracy=.. single_image_accuracy=.. window_accuracy=.. filter_accuracy=..
# Usage: scripts/evaluate_places.sh [CAMERA=omni|perspective] [CAMERA_RATE_HZ=1]
# About 5 minutes on two cores. Needs a built workspace (scripts/setup.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
CAMERA="${1:-omni}"
RATE="${2:-1}"
OUT="$AP_ROOT/results/places/$CAMERA"
make_tmp
mkdir -p "$OUT"
LIGHTS="$INDOOR_LIGHTS"
for L in $LIGHTS; do
  s=$(indoor_seed_base "$L")
  "$BIN/simulate_indoor" --lighting "$L" --seed $((s + 1)) --camera "$CAMERA" --camera_rate_hz "$RATE" \
    --output "$TMP/train.bag" --overwrite 2> /dev/null | tail -n 1
  rm -f "$OUT/$L.sqlite"
  "$BIN/train_places" --bag "$TMP/train.bag" --database "$OUT/$L.sqlite" --images_per_place 15 \
    $([ "$CAMERA" = omni ] && echo "--mask auto") 2> /dev/null | tail -n 1
  rm -f "$TMP/train.bag"
done
csv="$OUT/lighting.csv"
echo "train,test,accuracy,mean_confidence,best_space,best_method,single_image_accuracy,window_accuracy,filter_accuracy,queries_per_s" > "$csv"
for T in $LIGHTS; do
  s=$(indoor_seed_base "$T")
  "$BIN/simulate_indoor" --lighting "$T" --seed $((s + 2)) --camera "$CAMERA" --camera_rate_hz "$RATE" \
    --output "$TMP/test.bag" --overwrite 2> /dev/null | tail -n 1
  for L in $LIGHTS; do
    dir="$OUT/${L}_$T"
    mkdir -p "$dir"
    "$BIN/evaluate_places" --database "$OUT/$L.sqlite" --bag "$TMP/test.bag" --images_per_place 15 \
      --output "$dir" > "$dir/log.txt" 2>&1
    line="$(tail -n 1 "$dir/log.txt")"
    echo "$L,$T,$(summary_value "$line" accuracy),$(summary_value "$line" mean_confidence),$(summary_value "$line" best_space),$(summary_value "$line" best_method),$(summary_value "$line" single_image_accuracy),$(summary_value "$line" window_accuracy),$(summary_value "$line" filter_accuracy),$(summary_value "$line" queries_per_s)" >> "$csv"
    echo "places_lighting: camera=$CAMERA train=$L test=$T accuracy=$(summary_value "$line" accuracy) single_image_accuracy=$(summary_value "$line" single_image_accuracy) window_accuracy=$(summary_value "$line" window_accuracy) filter_accuracy=$(summary_value "$line" filter_accuracy)"
  done
  rm -f "$TMP/test.bag"
done
echo "evaluate_places.sh: paper tables (same lighting) in $OUT/cloudy_cloudy/log.txt, 3 x 3 in $csv"
