#!/usr/bin/env bash
# The tracking experiments of papers/001 section 3.4 in the tracking simulator, against OpenCV's
# CamShift: for each scenario (circles, lambertian_rectangle, distractor) the dynamics are learnt
# from a training sequence (seed 100, learn_tracking_dynamics), then SEEDS test sequences are run
# with the paper's CONDENSATION tracker (default and learnt dynamics), the elliptical head tracker
# and the box tracker (evaluate_tracking's default). Real sequences: evaluate_tracking_benchmark.sh.
# With Debian's opencv-doc installed, the head tracker and CONDENSATION also run on its face video
# (Megamind.avi, from frame 110; no ground truth there: lost frames and speed only).
# Writes results/tracking/<scenario>_<seed>_<tracker>/ (frames.csv, iou.png, strip.png) and
# results/tracking/table.csv; prints one line per run:
#   tracking: scenario=S seed=N tracker=T mean_iou=.. success_rate=.. lost_frames=.. fps=.. camshift_mean_iou=.. camshift_success_rate=..
# Usage: scripts/evaluate_tracking.sh [SEEDS="1 2 3 4 5 6"]   (~10 minutes on two cores)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
SEEDS="${1:-1 2 3 4 5 6}"
OUT="$AP_ROOT/results/tracking"
make_tmp
mkdir -p "$OUT"
csv="$OUT/table.csv"
echo "scenario,seed,tracker,mean_iou,success_rate,lost_frames,fps,camshift_mean_iou,camshift_success_rate,camshift_fps,frames" > "$csv"
run() {  # scenario seed tracker args...
  local s="$1" n="$2" t="$3"
  shift 3
  local dir="$OUT/${s}_${n}_$t"
  mkdir -p "$dir"
  "$BIN/evaluate_tracking" "$@" --output "$dir" > "$dir/log.txt" 2>&1 || { echo "tracking: $s $n $t failed (see $dir/log.txt)"; return; }
  local line
  line="$(grep '^evaluate_tracking:' "$dir/log.txt" | tail -n 1)"
  local keys="mean_iou success_rate lost_frames fps camshift_mean_iou camshift_success_rate camshift_fps frames"
  local row="$s,$n,$t" msg="tracking: scenario=$s seed=$n tracker=$t"
  for k in $keys; do
    row="$row,$(summary_value "$line" "$k")"
    msg="$msg $k=$(summary_value "$line" "$k")"
  done
  echo "$row" >> "$csv"
  echo "$msg"
}
for S in circles lambertian_rectangle distractor; do
  "$BIN/simulate_tracking" --scenario "$S" --seed 100 --output "$TMP/train.bag" --overwrite > /dev/null
  "$BIN/learn_tracking_dynamics" --bag "$TMP/train.bag" --output "$OUT/dynamics_$S.yaml" --overwrite | tail -n 1
  rm -f "$TMP/train.bag"
  # The paper's first experiment used RGB, the others (B-G, G-R, R+G+B).
  SPACE=opponent
  [ "$S" = circles ] && SPACE=rgb
  for N in $SEEDS; do
    "$BIN/simulate_tracking" --scenario "$S" --seed "$N" --output "$TMP/test.bag" --overwrite > /dev/null
    run "$S" "$N" condensation --bag "$TMP/test.bag" --mode condensation --peers camshift --color_space "$SPACE"
    run "$S" "$N" condensation_learnt --bag "$TMP/test.bag" --mode condensation --peers camshift --color_space "$SPACE" --dynamics "$OUT/dynamics_$S.yaml"
    run "$S" "$N" ellipse --bag "$TMP/test.bag" --mode ellipse --peers camshift --color_space "$SPACE"
    run "$S" "$N" box --bag "$TMP/test.bag" --mode box --peers camshift
    rm -f "$TMP/test.bag"
  done
done
FACE=/usr/share/doc/opencv-doc/examples/data/Megamind.avi
if [ -f "$FACE" ]; then
  run megamind 0 ellipse --video "$FACE" --start_frame 110 --init 405,110,150,215 --mode ellipse --peers camshift
  run megamind 0 condensation --video "$FACE" --start_frame 110 --init 405,110,150,215 --mode condensation --peers camshift
fi
echo "evaluate_tracking.sh: table in $csv"
