#!/usr/bin/env bash
# Tables 3 and 5 of papers/002 in the indoor simulator: SIFT image-to-room classification of single
# images (mode single) and the appearance Monte Carlo localizer (mode mcl), trained on one run of the
# building in each lighting (night / cloudy / sunny, every image of the run a training frame) and
# tested on another run in each lighting: 3 x 3 tables of ImageCLEF scores. Databases are made once
# (results/room_classification/<lighting>.sqlite; delete them to retrain). Writes
# results/room_classification/<mode>/<train>_<test>/ and results/room_classification/table.csv;
# prints one line per mode and pair:
#   room_classification: mode=M train=L test=L score=.. correct=.. misclassified=.. not_classified=.. frames=.. frames_per_s=..
# Usage: scripts/evaluate_room_classification.sh [CAMERA_RATE_HZ=2] [MODES="single mcl"]
#            [STRUCTURE_WEIGHT=0]
# STRUCTURE_WEIGHT > 0 joins the line-structure cues (section 4.1.2) to SIFT; its runs go to
# <mode>_structure<W>/ and the table's `mode` column reads e.g. single+structure0.3.
# (~20 minutes on two cores for both modes)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
RATE="${1:-2}"
MODES="${2:-single mcl}"
SW="${3:-0}"
SUFFIX=""
if [ "$SW" != "0" ]; then SUFFIX="+structure$SW"; fi
OUT="$AP_ROOT/results/room_classification"
make_tmp
mkdir -p "$OUT"
LIGHTS="$INDOOR_LIGHTS"
for L in $LIGHTS; do
  [ -f "$OUT/$L.sqlite" ] && continue
  "$BIN/simulate_indoor" --lighting "$L" --seed $(($(indoor_seed_base "$L") + 1)) --camera_rate_hz "$RATE" \
    --output "$TMP/train.bag" --overwrite 2> /dev/null > /dev/null
  "$BIN/train_places" --bag "$TMP/train.bag" --database "$OUT/$L.sqlite" --images_per_place 0 \
    --features --spaces hsv 2> /dev/null | tail -n 1
  rm -f "$TMP/train.bag"
done
csv="$OUT/table.csv"
[ -f "$csv" ] || echo "mode,train,test,score,correct,misclassified,not_classified,frames,score_per_frame,frames_per_s" > "$csv"
for T in $LIGHTS; do
  "$BIN/simulate_indoor" --lighting "$T" --seed $(($(indoor_seed_base "$T") + 2)) --camera_rate_hz "$RATE" \
    --output "$TMP/test.bag" --overwrite 2> /dev/null > /dev/null
  for M in $MODES; do
    for L in $LIGHTS; do
      dir="$OUT/$M${SUFFIX/+/_}/${L}_$T"
      mkdir -p "$dir"
      "$BIN/evaluate_room_classification" --database "$OUT/$L.sqlite" --bag "$TMP/test.bag" \
        --mode "$M" --structure_weight "$SW" --output "$dir" > "$dir/log.txt" 2>&1
      line="$(tail -n 1 "$dir/log.txt")"
      echo "$M$SUFFIX,$L,$T,$(summary_value "$line" score),$(summary_value "$line" correct),$(summary_value "$line" misclassified),$(summary_value "$line" not_classified),$(summary_value "$line" frames),$(summary_value "$line" score_per_frame),$(summary_value "$line" frames_per_s)" >> "$csv"
      echo "room_classification: mode=$M$SUFFIX train=$L test=$T score=$(summary_value "$line" score) correct=$(summary_value "$line" correct) misclassified=$(summary_value "$line" misclassified) not_classified=$(summary_value "$line" not_classified) frames=$(summary_value "$line" frames) frames_per_s=$(summary_value "$line" frames_per_s)"
    done
  done
  rm -f "$TMP/test.bag"
done
echo "evaluate_room_classification.sh: table in $csv"
