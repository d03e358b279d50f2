#!/usr/bin/env bash
# Runs rbpf_localizer's offline evaluation (evaluate_localization) on the bundled field bags and on a
# kidnap bag made by the simulator (fixed seed): from a global start with seed 1 (plotted: error.png,
# field.png), from a global start with seeds 2..SEEDS (how often a global start converges), and from
# the true start pose (tracking); then kidnap recovery over KIDNAPS simulated kidnaps x SEEDS seeds,
# by default (the relocalization check every 1 s) and with the check off. Writes results/localization/summary.md. Needs a
# built workspace (scripts/setup.sh).
# Usage: scripts/evaluate_localization.sh [--output DIR] [--particles N] [--threads T] [--seeds N]
#                                         [--kidnaps K]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
OUT="$AP_ROOT/results/localization"
PARTICLES=500
THREADS=0
SEEDS=5
KIDNAPS=4
while [ $# -gt 0 ]; do
  case "$1" in
    --output) OUT="$2"; shift 2 ;;
    --particles) PARTICLES="$2"; shift 2 ;;
    --threads) THREADS="$2"; shift 2 ;;
    --seeds) SEEDS="$2"; shift 2 ;;
    --kidnaps) KIDNAPS="$2"; shift 2 ;;
    *) echo "evaluate_localization.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ "$THREADS" = 0 ] && THREADS="$(nproc)"
mkdir -p "$OUT"
cd "$AP_ROOT"
KIDNAP="$OUT/field_kidnap.bag"
[ -f "$KIDNAP" ] || "$BIN/simulate_field" --script kidnap --seed 4 --duration_s 20 --rate_hz 4 \
  --output "$KIDNAP" > /dev/null
key() { grep -oE " $1=[-0-9.]+" | head -1 | cut -d= -f2; }
summary="$OUT/summary.md"
{
  echo "# rbpf_localizer ($PARTICLES particles, $THREADS threads)"
  echo
  md_header "bag" "filter" "global starts converged (of $SEEDS seeds)" "of them within 5 s" "seed 1: converged after (s)" "re-converged after kidnap (s)" "median position error (m)" "median heading error (deg)" "classification rate" "frames/s" "from the true start: converged after (s) / median position error (m) / heading (deg)"
} > "$summary"
for bag in rosbag/field_bright.bag rosbag/field_dark.bag rosbag/field_switching.bag "$KIDNAP"; do
  name="$(basename "$bag" .bag)"
  for filter in switching single; do
    run="$OUT/${name}_$filter"
    common=(--bag "$bag" --particles "$PARTICLES" --threads "$THREADS" --filter "$filter")
    line="$("$BIN/evaluate_localization" "${common[@]}" --output "$run" | tail -n 1)"
    echo "$name $filter: $line"
    converged=0
    within=0
    count() {  # a run's summary line: converged at all, and within 5 s of the start
      local c
      c="$(echo "$1" | key converged_after_s)"
      [ "$c" != "-1.00" ] && converged=$((converged + 1))
      [ "$c" != "-1.00" ] && awk -v c="$c" 'BEGIN { exit !(c <= 5.0) }' && within=$((within + 1))
      return 0
    }
    count "$line"
    for seed in $(seq 2 "$SEEDS"); do
      other="$("$BIN/evaluate_localization" "${common[@]}" --seed "$seed" \
        --output "$OUT/seeds/${name}_${filter}_$seed" | tail -n 1)"
      count "$other"
    done
    track="$("$BIN/evaluate_localization" "${common[@]}" --init truth \
      --output "$OUT/tracking/${name}_$filter" | tail -n 1)"
    echo "$name $filter: $converged of $SEEDS global starts converged ($within within 5 s); from the true start: $track"
    echo "| $name | $filter | $converged | $within | $(echo "$line" | key converged_after_s) | $(echo "$line" | key reconverged_after_kidnap_s) | $(echo "$line" | key median_position_error_m) | $(echo "$line" | key median_heading_error_deg) | $(echo "$line" | key classification_rate) | $(echo "$line" | key frames_per_s) | $(echo "$track" | key converged_after_s) / $(echo "$track" | key median_position_error_m) / $(echo "$track" | key median_heading_error_deg) |" >> "$summary"
    python3 "$AP_ROOT/scripts/plot_localization.py" "$run" config/field_4legged.yaml "$name, $filter filter, global start"
  done
done
# Kidnap recovery over several simulated kidnaps (simulator seeds 4..3+KIDNAPS; each robot is
# teleported at 10 s to a random free pose at least 1.5 m away), seeds 1..SEEDS each, by default
# (the relocalization check every 1 s) and with the check off: how many re-converge within 5 s.
recovery() {  # LABEL [extra evaluate_localization arguments]
  local label="$1" within=0 total=0 times="" bag k
  shift
  for sim in $(seq 4 $((3 + KIDNAPS))); do
    bag="$OUT/field_kidnap_sim$sim.bag"
    [ "$sim" = 4 ] && bag="$KIDNAP"  # the table's kidnap bag
    [ -f "$bag" ] || "$BIN/simulate_field" --script kidnap --seed "$sim" --duration_s 20 --rate_hz 4 \
      --output "$bag" > /dev/null
    for seed in $(seq 1 "$SEEDS"); do
      k="$("$BIN/evaluate_localization" --bag "$bag" --particles "$PARTICLES" --threads "$THREADS" \
        --seed "$seed" "$@" --output "$OUT/recovery/${label}_sim${sim}_$seed" | tail -n 1 |
        key reconverged_after_kidnap_s)"
      times="$times $k"
      total=$((total + 1))
      awk -v k="$k" 'BEGIN { exit !(k >= 0 && k <= 5.0) }' && within=$((within + 1))
    done
  done
  echo "$label: $within of $total kidnaps re-converged within 5 s (seconds after the kidnap, -1 = never:$times)"
}
recovery_default="$(recovery default)"
recovery_off="$(recovery check_off --relocalization_interval_s 0)"
echo "field_kidnap switching, $recovery_default"
echo "field_kidnap switching, $recovery_off"
{
  echo
  echo "Kidnap recovery, switching filter, $KIDNAPS simulated kidnaps (simulate_field --script kidnap --seed 4..$((3 + KIDNAPS))) x $SEEDS seeds:"
  echo
  echo "- by default (the relocalization check every 1 s): ${recovery_default#default: }"
  echo "- with the check off (\`--relocalization_interval_s 0\`): ${recovery_off#check_off: }"
  echo
  echo "converged after: the first frame after which the position error stays below 0.3 m to the end, or, on"
  echo "the kidnap bag, until the kidnap (-1: never). Errors are medians over the converged frames."
  echo "frames/s includes the global search over the first images. Plots (seed 1): */error.png, */field.png."
} >> "$summary"
echo "evaluate_localization.sh: wrote $summary"
