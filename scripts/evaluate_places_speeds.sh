#!/usr/bin/env bash
# How the traversal protocol's default configuration holds when the query is driven at another
# speed than the reference: from a dataset of two aligned traversals (frame i of one is frame i of
# the other, as in Nordland), it makes query lists that show the query traversal at each SPEED
# (query frame k is query frame floor(SPEED k)) with the matching ground truth (reference frame
# floor(SPEED k) +- TOLERANCE), and runs `evaluate_places --reference REF --query LIST
# --ground_truth GT` with its defaults on each. The frames stay where they are (only lists of their
# paths are written, to a temporary folder).
# Then the drives a real route has beside a steady speed (PROFILES), each at the reference's speed
# otherwise: `stops` (the query stands still for 15 frames every 100), `slow` (a stretch of a
# tenth of the route at half speed), `reverse` (it backs up 5% of the route, then drives on over
# it again), `jump` (a third of the route is skipped: a kidnap). For these the table puts the
# route filter's recall (--method route) beside the sequence matcher's, from the same run.
# Prints each run's summary line and Markdown tables; writes results/places_speeds/<dataset>/.
# Usage: [SPEEDS="0.6 0.73 1 1.37 2"] [PROFILES="stops slow reverse jump"] [TOLERANCE=1]
#   scripts/evaluate_places_speeds.sh REF_DIR QUERY_DIR [EXTRA evaluate_places OPTIONS]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
SPEEDS="${SPEEDS:-0.6 0.73 1 1.37 2}"
PROFILES="${PROFILES:-stops slow reverse jump}"
TOLERANCE="${TOLERANCE:-1}"
[ "$#" -ge 2 ] || { echo "usage: $0 REF_DIR QUERY_DIR [evaluate_places options]"; exit 2; }
REF="${1%/}"; QUERY="${2%/}"; shift 2
[ -x "$BIN/evaluate_places" ] || "$AP_ROOT/scripts/setup.sh" || exit 1
name="$(basename "$(dirname "$REF")")"
OUT="$AP_ROOT/results/places_speeds/$name"
make_tmp
mkdir -p "$OUT"
mapfile -t frames < <(find "$QUERY" -maxdepth 1 -type f \( -iname '*.png' -o -iname '*.jpg' -o -iname '*.jpeg' -o -iname '*.bmp' -o -iname '*.ppm' \) | LC_ALL=C sort)
n="${#frames[@]}"
[ "$n" -gt 0 ] || { echo "evaluate_places_speeds: no images in $QUERY"; exit 1; }
# One run: the query list the ground truth GT names (its query frames in order), evaluate_places on
# it in $OUT/NAME; sets `dir` and `line` (the summary line); fails when the tool did.
run_query() {  # GT NAME [evaluate_places options]
  local gt="$1" name="$2" list="$TMP/$2.csv"
  shift 2
  echo "image_path" > "$list"
  awk -F, 'NR == FNR { f[NR - 1] = $0; next } { print f[$2 - 1] }' <(printf '%s\n' "${frames[@]}") "$gt" >> "$list"
  dir="$OUT/$name"
  mkdir -p "$dir"
  "$BIN/evaluate_places" --reference "$REF" --query "$list" --ground_truth "$gt" --output "$dir" "$@" > "$dir/log.txt" 2>&1 \
    || { echo "evaluate_places_speeds: $name failed: $(tail -n 1 "$dir/log.txt")" >&2; return 1; }
  line="$(tail -n 1 "$dir/log.txt")"
  echo "$name $line"
}
table="$(md_header "query speed (x reference)" queries recall@1 recall@5 "PR AUC" "recall at 100% precision")"
for s in $SPEEDS; do
  gt="$TMP/gt_$s.csv"
  # Query frame k shows frame floor(s k); ground truth counts from 1 (Nordland's convention).
  awk -v s="$s" -v n="$n" -v t="$TOLERANCE" 'BEGIN { for (k = 0; int(s * k) < n; ++k) { i = int(s * k); print k + 1 "," i + 1 "," t } }' > "$gt"
  run_query "$gt" "speed_$s" "$@" || continue
  table+=$'\n'"| $s | $(summary_value "$line" queries) | $(summary_value "$line" recall_at_1) | $(summary_value "$line" recall_at_5) | $(summary_value "$line" pr_auc) | $(summary_value "$line" recall_at_full_precision) |"
done
echo "$table" | tee "$OUT/table.md"
# The drives: the frame query frame k shows, for k = 0, 1, ... (0-based, within 0 .. n - 1).
profile_frames() {  # profile n
  awk -v p="$1" -v n="$2" 'BEGIN {
    if (p == "stops") {
      for (i = 0; i < n; ++i) { print i; if (i % 100 == 99) for (r = 0; r < 14; ++r) print i }
    } else if (p == "slow") {
      a = int(0.45 * n); b = a + int(0.1 * n)
      for (i = 0; i < a; ++i) print i
      for (k = 0; a + int(k / 2) < b; ++k) print a + int(k / 2)
      for (i = b; i < n; ++i) print i
    } else if (p == "reverse") {
      a = int(0.5 * n); back = int(0.05 * n)
      for (i = 0; i <= a; ++i) print i
      for (i = a - 1; i >= a - back; --i) print i
      for (i = a - back + 1; i < n; ++i) print i
    } else if (p == "jump") {
      a = int(0.3 * n); b = int(0.63 * n)
      for (i = 0; i < a; ++i) print i
      for (i = b; i < n; ++i) print i
    } else { print "unknown profile " p > "/dev/stderr"; exit 1 }
  }'
}
method_recall() { awk -v m="$1" '$1 == m { print $2; exit }' "$2"; }
ptable="$(md_header "drive" queries "sequence recall@1" "route filter recall@1" "sequence recall@5" "route filter recall@5")"
for p in $PROFILES; do
  gt="$TMP/gt_$p.csv"
  profile_frames "$p" "$n" | awk -v t="$TOLERANCE" '{ print NR "," $1 + 1 "," t }' > "$gt" || continue
  run_query "$gt" "drive_$p" "$@" || continue
  ptable+=$'\n'"| $p | $(summary_value "$line" queries) | $(method_recall sequence "$dir/log.txt") | $(method_recall route "$dir/log.txt") | $(awk '$1 == "sequence" { print $3; exit }' "$dir/log.txt") | $(awk '$1 == "route" { print $3; exit }' "$dir/log.txt") |"
done
if [ -n "$PROFILES" ]; then echo "$ptable" | tee "$OUT/drives.md"; fi
echo "evaluate_places_speeds: tolerance ${TOLERANCE} reference frames; runs in $OUT"
