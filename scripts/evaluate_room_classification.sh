#!/usr/bin/env bash
# Table 3 of papers/002 in the indoor simulator: SIFT image-to-room classification (single images),
# trained on one run of the building in each lighting (night / cloudy / sunny, every image of the
# run as a training frame) and tested on another run in each lighting: a 3 x 3 table of ImageCLEF
# scores. Writes results/room_classification/<train>_<test>/ and results/room_classification/table.csv;
# prints one line per pair:
#   room_classification: train=L test=L score=.. correct=.. misclassified=.. not_classified=.. frames=.. frames_per_s=..
# Usage: scripts/evaluate_room_classification.sh [CAMERA_RATE_HZ=2]   (~10 minutes on two cores)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
BIN="$AP_WS/devel/lib/adaptive_perception"
RATE="${1:-2}"
OUT="$AP_ROOT/results/room_classification"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$OUT"
LIGHTS="night cloudy sunny"
seed_of() { case "$1" in night) echo 0 ;; cloudy) echo 10 ;; sunny) echo 20 ;; esac; }
for L in $LIGHTS; do
  "$BIN/simulate_indoor" --lighting "$L" --seed $(($(seed_of "$L") + 1)) --camera_rate_hz "$RATE" \
    --output "$TMP/train.bag" --overwrite 2> /dev/null > /dev/null
  rm -f "$OUT/$L.sqlite"
  "$BIN/train_places" --bag "$TMP/train.bag" --database "$OUT/$L.sqlite" --images_per_place 0 \
    --features --spaces hsv 2> /dev/null | tail -n 1
  rm -f "$TMP/train.bag"
done
csv="$OUT/table.csv"
echo "train,test,score,correct,misclassified,not_classified,frames,score_per_frame,frames_per_s" > "$csv"
for T in $LIGHTS; do
  "$BIN/simulate_indoor" --lighting "$T" --seed $(($(seed_of "$T") + 2)) --camera_rate_hz "$RATE" \
    --output "$TMP/test.bag" --overwrite 2> /dev/null > /dev/null
  for L in $LIGHTS; do
    dir="$OUT/${L}_$T"
    mkdir -p "$dir"
    "$BIN/evaluate_room_classification" --database "$OUT/$L.sqlite" --bag "$TMP/test.bag" \
      --output "$dir" > "$dir/log.txt" 2>&1
    line="$(tail -n 1 "$dir/log.txt")"
    get() { echo "$line" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
    echo "$L,$T,$(get score),$(get correct),$(get misclassified),$(get not_classified),$(get frames),$(get score_per_frame),$(get frames_per_s)" >> "$csv"
    echo "room_classification: train=$L test=$T score=$(get score) correct=$(get correct) misclassified=$(get misclassified) not_classified=$(get not_classified) frames=$(get frames) frames_per_s=$(get frames_per_s)"
  done
  rm -f "$TMP/test.bag"
done
echo "evaluate_room_classification.sh: table in $csv"
