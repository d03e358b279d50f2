#!/usr/bin/env bash
# Runs the line extractor over the four real CARMEN logs in data/laser/: converts each with carmen_to_bag,
# then evaluate_lines (speed, segments per scan, one scan drawn as PNG). Writes results/real_logs/.
# Needs a built workspace (scripts/setup.sh).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
BIN="$AP_WS/devel/lib/adaptive_perception"
OUT="$AP_ROOT/results/real_logs"
mkdir -p "$OUT"
summary="$OUT/summary.txt"
: > "$summary"
for log in intel fr079 mit-csail fr-clinic_robotlaser; do
  "$BIN/carmen_to_bag" --input "$AP_ROOT/data/laser/$log.clf.bz2" --output "$OUT/$log.bag" --overwrite --max_issues 3 \
    2> "$OUT/$log.issues.txt" | tee -a "$summary"
  "$BIN/evaluate_lines" --bag "$OUT/$log.bag" --output "$OUT/$log" --name "$log" | tail -n 1 | sed "s/^/$log /" | tee -a "$summary"
  rm -f "$OUT/$log.bag"
done
echo "evaluate_real_logs: plots in $OUT/<log>/scan.png, summary in $summary"
