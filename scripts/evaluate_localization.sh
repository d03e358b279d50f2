#!/usr/bin/env bash
# Runs rbpf_localizer's offline evaluation (evaluate_localization, global start) on the bundled field
# bags and on a kidnap bag made by the simulator (fixed seed), plots each run (error.png, field.png) and
# writes results/localization/summary.md. Needs a built workspace (scripts/setup.sh).
# Usage: scripts/evaluate_localization.sh [--output DIR] [--particles N] [--threads T]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
OUT="$AP_ROOT/results/localization"
PARTICLES=500
THREADS=0
while [ $# -gt 0 ]; do
  case "$1" in
    --output) OUT="$2"; shift 2 ;;
    --particles) PARTICLES="$2"; shift 2 ;;
    --threads) THREADS="$2"; shift 2 ;;
    *) echo "evaluate_localization.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ "$THREADS" = 0 ] && THREADS="$(nproc)"
BIN="$AP_WS/devel/lib/adaptive_perception"
mkdir -p "$OUT"
cd "$AP_ROOT"
KIDNAP="$OUT/field_kidnap.bag"
[ -f "$KIDNAP" ] || "$BIN/simulate_field" --script kidnap --seed 4 --duration_s 20 --rate_hz 4 \
  --output "$KIDNAP" > /dev/null
key() { grep -oE " $1=[-0-9.]+" | head -1 | cut -d= -f2; }
summary="$OUT/summary.md"
{
  echo "# rbpf_localizer from a global start ($PARTICLES particles, $THREADS threads)"
  echo
  echo "| bag | filter | converged after (s) | re-converged after kidnap (s) | median position error (m) | median heading error (deg) | classification rate | frames/s |"
  echo "|---|---|---|---|---|---|---|---|"
} > "$summary"
for bag in rosbag/field_bright.bag rosbag/field_dark.bag rosbag/field_switching.bag "$KIDNAP"; do
  name="$(basename "$bag" .bag)"
  for filter in switching single; do
    run="$OUT/${name}_$filter"
    line="$("$BIN/evaluate_localization" --bag "$bag" --particles "$PARTICLES" --threads "$THREADS" \
      --filter "$filter" --output "$run" | tail -n 1)"
    echo "$name $filter: $line"
    echo "| $name | $filter | $(echo "$line" | key converged_after_s) | $(echo "$line" | key reconverged_after_kidnap_s) | $(echo "$line" | key median_position_error_m) | $(echo "$line" | key median_heading_error_deg) | $(echo "$line" | key classification_rate) | $(echo "$line" | key frames_per_s) |" >> "$summary"
    python3 "$AP_ROOT/scripts/plot_localization.py" "$run" config/field_4legged.yaml "$name, $filter filter, global start"
  done
done
{
  echo
  echo "converged after: the first frame after which the position error stays below 0.3 m to the end (-1: never)."
  echo "Errors are medians over the converged frames. Plots: */error.png, */field.png."
} >> "$summary"
echo "evaluate_localization.sh: wrote $summary"
