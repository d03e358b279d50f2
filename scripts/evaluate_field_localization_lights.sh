#!/usr/bin/env bash
# Global localization on a real NAO session under other lights: the session's images as a camera
# would see them under a dimmer, brighter, warmer, cooler, greener or pinker light (each image's R,
# G and B scaled, or its levels raised to a power: evaluate_field_localization --light_rgb /
# --light_gamma), each light run through evaluate_field_localization.sh (leave one point out).
# Prints one row per light (each point's position error in metres) and a summary line:
#   evaluate_field_localization_lights.sh: lights=.. points=.. within_0_5m=..
# Usage: scripts/evaluate_field_localization_lights.sh SESSION_DIR [--output DIR] [TOOL OPTIONS...]
#   SESSION_DIR: as for evaluate_field_localization.sh (never copied, never written).
#   TOOL OPTIONS: passed to evaluate_field_localization (e.g. --balance_to_paint false, the
#   localizer without the paint's white balance, for the comparison in docs/field_localization.md).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
die() { echo "evaluate_field_localization_lights.sh: $*" >&2; exit 2; }
[ $# -ge 1 ] || { sed -n '2,11p' "$0"; exit 2; }
SESSION="$1"; shift
OUT="$AP_ROOT/results/field_localization_lights"
if [ "${1:-}" = "--output" ]; then
  [ $# -ge 2 ] || die "--output needs a folder"
  OUT="$2"; shift 2
fi
[ -d "$SESSION" ] || die "no session folder $SESSION"
mkdir -p "$OUT"
# name, R G B gains, gamma. The tints are of the size a camera's own white balance leaves (a tenth
# to a quarter of a channel) and twice that; the brightness of a light 0.55 to 1.4 times as strong.
LIGHTS="as_recorded:1,1,1:1 dimmer_0.7:0.7,0.7,0.7:1 dimmer_0.55:0.55,0.55,0.55:1
brighter_1.4:1.4,1.4,1.4:1 darker_gamma_1.6:1,1,1:1.6 warm:1,0.88,0.72:1
warm_strong:0.75,0.6,0.42:1 cool:0.85,0.95,1.1:1 cool_strong:0.8,0.9,1.1:1 green:0.9,1,0.9:1
pink:1,0.88,1:1"
md_header light "position error per point (m)" "within 0.5 m"
lights=0 points=0 within=0
for light in $LIGHTS; do
  IFS=: read -r name rgb gamma <<< "$light"
  line="$("$AP_ROOT/scripts/evaluate_field_localization.sh" "$SESSION" --output "$OUT/$name" \
    --light_rgb ${rgb//,/ } --light_gamma "$gamma" "$@" | tail -n 1)"
  errs="$(tail -n +2 "$OUT/$name/points.csv" | cut -d, -f1,6 | tr '\n' ' ')"
  n="$(summary_value "$line" images)"; w="$(summary_value "$line" within_0_5m)"
  [ -n "$n" ] && [ -n "$w" ] || die "$name: evaluate_field_localization.sh printed no summary"
  echo "| $name | $errs | $w of $n |"
  lights=$((lights + 1)); points=$((points + n)); within=$((within + w))
done
echo "evaluate_field_localization_lights.sh: lights=$lights points=$points within_0_5m=$within"
