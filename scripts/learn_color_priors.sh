#!/usr/bin/env bash
# Reproduces the committed lighting priors in config/color_priors/: simulates N earlier environments
# (`simulate_field --environment_seed 1..N`), each once bright and once dark, then learns K = 2 priors
# (dark, bright) and the single-filter prior (all) from them. The paper used 44 hand-labelled data sets;
# so do we by default (22 environments x 2 lighting conditions).
# Usage: scripts/learn_color_priors.sh [--environments N] [--output_dir DIR]   (needs a built workspace)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
N=22
OUT="$AP_ROOT/config/color_priors"
while [ $# -gt 0 ]; do
  case "$1" in
    --environments) N="$2"; shift 2 ;;
    --output_dir) OUT="$2"; shift 2 ;;
    *) echo "usage: $0 [--environments N] [--output_dir DIR]" >&2; exit 2 ;;
  esac
done
BAGS="$AP_ROOT/results/prior_bags"
rm -rf "$BAGS"; mkdir -p "$BAGS"
for e in $(seq 1 "$N"); do
  for script in bright dark; do
    "$BIN/simulate_field" --script "$script" --environment_seed "$e" --seed "$((100 + e))" --duration_s 6 \
      --rate_hz 2 --output "$BAGS/env$(printf %02d "$e")_$script.bag" > /dev/null
  done
done
"$BIN/learn_color_priors" --bag_dir "$BAGS" --k 2 --names dark,bright --output_dir "$OUT" --overwrite
