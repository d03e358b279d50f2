#!/usr/bin/env bash
# Global localization on a real NAO session, left one point out: each point's top image goes through
# evaluate_field_localization (a global start from nothing, 30 images of the standing robot) with
# the camera calibrated without that point where the calibration used it (calibrate_head_camera.py's
# without_<point> fits written into a copy of config/cameras/nao_v6_top.yaml), with the shipped
# camera otherwise. Prints one line per point and a summary line:
#   evaluate_field_localization.sh: images=.. within_0_5m=.. median_position_error_m=..
# Usage: scripts/evaluate_field_localization.sh SESSION_DIR [--output DIR] [TOOL OPTIONS...]
#   SESSION_DIR: a session of the NAO field development set (puntN folders with imagetop.jpg and
#   their motion-capture CSVs), e.g. ../shared/data/field/nao_spl_field/red1. Never copied.
#   TOOL OPTIONS: passed to evaluate_field_localization (e.g. --seed 2).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
die() { echo "evaluate_field_localization.sh: $*" >&2; exit 2; }
[ $# -ge 1 ] || { sed -n '2,11p' "$0"; exit 2; }
SESSION="$1"; shift
OUT="$AP_ROOT/results/field_localization"
if [ "${1:-}" = "--output" ]; then
  [ $# -ge 2 ] || die "--output needs a folder"
  OUT="$2"; shift 2
fi
[ -d "$SESSION" ] || die "no session folder $SESSION"
# Absolute before the cd below.
SESSION="$(cd "$SESSION" && pwd)"
mkdir -p "$OUT"
OUT="$(cd "$OUT" && pwd)"
make_tmp
cd "$AP_ROOT"
CAMERA=config/cameras/nao_v6_top.yaml
python3 scripts/nao_field_list.py "$SESSION" "$TMP/all.csv" > /dev/null
# The leave-one-point-out cameras: fx, the pan axis's height, the camera's pitch and the torso
# pitch it holds at (the inertial unit's) of each without_<point> fit.
FIT='s/.*fit=without_\([^ ]*\) .*fx_px=\([^ ]*\) .*base_to_pan_z_m=\([^ ]*\)'
FIT+=' camera_pitch_rad=\([^ ]*\) torso_pitch_reference_rad=\([^ ]*\) .*/\1 \2 \3 \4 \5/p'
python3 scripts/calibrate_head_camera.py data/calibration/nao_v6_top_marks.csv > "$TMP/fits.txt"
sed -n "$FIT" "$TMP/fits.txt" > "$TMP/without.txt"
# Every point the calibration used needs its camera fitted without it.
used="$(grep -c '^  punt[0-9]*: base_to_pan_z_m=' "$TMP/fits.txt" || true)"
[ "$(wc -l < "$TMP/without.txt")" -eq "$used" ] && [ "$used" -gt 0 ] ||
  die "calibrate_head_camera.py printed $used fitted points but not a without_ fit for each"
while read -r point fx z pitch torso; do
  sed -e "s/^fx_px: .*/fx_px: $fx/" -e "s/^fy_px: .*/fy_px: $fx/" \
      -e "s/^base_to_pan_m: .*/base_to_pan_m: [0.0, 0.0, $z]/" \
      -e "s/^camera_pitch_rad: .*/camera_pitch_rad: $pitch/" \
      -e "s/^torso_pitch_reference_rad: .*/torso_pitch_reference_rad: $torso/" \
      "$CAMERA" > "$TMP/without_$point.yaml"
  grep -q "^torso_pitch_reference_rad: $torso\$" "$TMP/without_$point.yaml" ||
    die "$CAMERA has no torso_pitch_reference_rad line for the without_$point fit"
done < "$TMP/without.txt"
header="$(head -n 1 "$TMP/all.csv")"
# The list carries each picture's torso pitch (the inertial unit's), which leans the camera: the
# goal's own measure of the lean is then left off (goal_pitch_correction), unless asked for. Its
# residual there, -0.008 to 0.0005 rad, is the goal's error, not the lean's (the inertial unit
# agrees with the calibration images within 0.001): docs/field_localization.md.
extra=(--goal_pitch_correction false)
for a in "$@"; do case "$a" in --goal_pitch_correction*) extra=() ;; esac; done
errors=()
printf 'point,camera,x_m,y_m,heading_deg,position_error_m,goals_seen,camera_pitch_offset_rad\n' |
  tee "$OUT/points.csv"
while IFS= read -r line; do
  point="$(echo "$line" | grep -o 'punt[0-9]*' | head -n 1)"
  camera="$CAMERA"
  [ -f "$TMP/without_$point.yaml" ] && camera="$TMP/without_$point.yaml"
  { echo "$header"; echo "$line"; } > "$TMP/$point.csv"
  "$BIN/evaluate_field_localization" --field config/field_spl_landmarks.yaml --camera "$camera" \
    --list "$TMP/$point.csv" --threads "$(nproc)" --output "$OUT/$point" "${extra[@]}" "$@" \
    > /dev/null
  row="$(tail -n 1 "$OUT/$point/images.csv")"
  IFS=, read -r _ x y heading _ _ _ _ error _ goals pitch _ <<< "$row"
  echo "$point,$(basename "$camera"),$x,$y,$heading,$error,$goals,$pitch" | tee -a "$OUT/points.csv"
  # (-1: the list gave no true position)
  awk -v e="$error" 'BEGIN { exit !(e >= 0) }' && errors+=("$error")
done < <(tail -n +2 "$TMP/all.csv" | grep imagetop)
within="$(printf '%s\n' "${errors[@]}" | awk 'NF && $1 <= 0.5' | wc -l)"
median="$(printf '%s\n' "${errors[@]}" | sort -g | awk 'NF {a[++n] = $1} END {
  if (n == 0) print -1; else if (n % 2) print a[(n + 1) / 2];
  else printf "%.3f\n", (a[n / 2] + a[n / 2 + 1]) / 2 }')"
echo "evaluate_field_localization.sh: images=$(($(wc -l < "$OUT/points.csv") - 1))" \
     "within_0_5m=$within median_position_error_m=$median"
