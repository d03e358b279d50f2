#!/usr/bin/env bash
# How the traversal protocol's default configuration holds on routes as short as a corridor filmed
# twice (the indoor route kept apart has 111 frames a traversal): from a dataset of two aligned
# traversals (frame i of one is frame i of the other, as in Nordland), it cuts both into consecutive
# disjoint routes of LENGTH frames, and runs `evaluate_places --reference SEGMENT --query SEGMENT
# --tolerance_frames TOLERANCE` with its defaults on each: a filter that must answer from its first
# query frame, with a likelihood calibrated on a short reference, over few frames of context.
# Prints each route's recall@1 for the route filter (the default), the sequence search and the
# single-image fused cue, their means, and a Markdown table; writes results/places_segments/<dataset>/.
# Only lists of the frames' paths are written (to a temporary folder); the frames stay where they are.
# Usage: [LENGTH=111] [TOLERANCE=2] scripts/evaluate_places_segments.sh REF_DIR QUERY_DIR [EXTRA evaluate_places OPTIONS]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
LENGTH="${LENGTH:-111}"
TOLERANCE="${TOLERANCE:-2}"
[ "$#" -ge 2 ] || { echo "usage: $0 REF_DIR QUERY_DIR [evaluate_places options]"; exit 2; }
[[ "$LENGTH" =~ ^[1-9][0-9]*$ ]] || { echo "evaluate_places_segments: LENGTH=$LENGTH is not a whole number of frames >= 1"; exit 2; }
[[ "$TOLERANCE" =~ ^[0-9]+$ ]] || { echo "evaluate_places_segments: TOLERANCE=$TOLERANCE is not a whole number of frames"; exit 2; }
REF="${1%/}"; QUERY="${2%/}"; shift 2
[ -x "$BIN/evaluate_places" ] || "$AP_ROOT/scripts/setup.sh" || exit 1
name="$(basename "$(dirname "$REF")")"
OUT="$AP_ROOT/results/places_segments/$name"
make_tmp
mkdir -p "$OUT"
list_images() {
  find "$1" -maxdepth 1 -type f \( -iname '*.png' -o -iname '*.jpg' -o -iname '*.jpeg' -o -iname '*.bmp' -o -iname '*.ppm' \) | LC_ALL=C sort
}
mapfile -t refs < <(list_images "$REF")
mapfile -t queries < <(list_images "$QUERY")
n="${#refs[@]}"
[ "$n" -eq "${#queries[@]}" ] || { echo "evaluate_places_segments: $REF has $n images, $QUERY ${#queries[@]}: not aligned"; exit 1; }
[ "$n" -ge "$LENGTH" ] || { echo "evaluate_places_segments: $n images, fewer than LENGTH=$LENGTH"; exit 1; }
recall() { awk -v m="$1" '$1 == m { print $2; exit }' "$2"; }
table="$(md_header "route (frames)" "route filter recall@1" "sequence recall@1" "fused recall@1")"
sums="0 0 0"; routes=0
for ((start = 0; start + LENGTH <= n; start += LENGTH)); do
  seg="$(printf '%05d-%05d' $((start + 1)) $((start + LENGTH)))"
  echo "image_path" > "$TMP/ref.csv"; echo "image_path" > "$TMP/query.csv"
  printf '%s\n' "${refs[@]:start:LENGTH}" >> "$TMP/ref.csv"
  printf '%s\n' "${queries[@]:start:LENGTH}" >> "$TMP/query.csv"
  dir="$OUT/$seg"
  mkdir -p "$dir"
  "$BIN/evaluate_places" --reference "$TMP/ref.csv" --query "$TMP/query.csv" \
    --tolerance_frames "$TOLERANCE" --output "$dir" "$@" > "$dir/log.txt" 2>&1 \
    || { echo "evaluate_places_segments: $seg failed: $(tail -n 1 "$dir/log.txt")" >&2; exit 1; }
  r="$(recall route "$dir/log.txt")"; s="$(recall sequence "$dir/log.txt")"; f="$(recall fused "$dir/log.txt")"
  [ -n "$r" ] && [ -n "$s" ] && [ -n "$f" ] \
    || { echo "evaluate_places_segments: $seg: a method's recall is missing from $dir/log.txt" >&2; exit 1; }
  echo "segment=$seg route=$r sequence=$s fused=$f"
  table+=$'\n'"| $seg | $r | $s | $f |"
  sums="$(echo "$sums $r $s $f" | awk '{ print $1 + $4, $2 + $5, $3 + $6 }')"
  routes=$((routes + 1))
done
means="$(echo "$sums" | awk -v k="$routes" '{ printf "%.3f %.3f %.3f", $1 / k, $2 / k, $3 / k }')"
read -r mr ms mf <<< "$means"
table+=$'\n'"| mean of $routes | $mr | $ms | $mf |"
echo "$table" | tee "$OUT/table.md"
echo "evaluate_places_segments: routes=$routes length=$LENGTH tolerance=$TOLERANCE route_recall_at_1=$mr sequence_recall_at_1=$ms fused_recall_at_1=$mf"
