#!/usr/bin/env bash
# Runs evaluate_places' traversal protocol (--reference A --query B, the default configuration,
# every method on the same frames) over every place-recognition dataset found in the folders
# given, and writes one table. A dataset is a folder holding
#   ref/ and query/             (the VPR tutorials' layout: Gardens Point's excerpt), or
#   exactly two image folders   (Nordland: summer/ winter/): the first in name order is the
#                               reference, the other the query;
# frame i of the query matches frames i - T .. i + T of the reference (T = TOLERANCE, default 1).
# A folder given may be a dataset itself or hold datasets. Writes results/places_traversals/:
#   <dataset>/            each run (results.yaml, queries.csv, pr_curves.csv, pr_curve.png, log.txt)
#   table.csv, table.md   one row per dataset and method: recall@1, recall@5, PR AUC, recall at
#                         100% precision, matching ms per query
# and prints each run's summary line and the Markdown table. The frames stay where they are
# (research-use terms: never copied into the project).
# Usage: [TOLERANCE=1] scripts/evaluate_places_traversals.sh DIR [DIR ...]
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
TOLERANCE="${TOLERANCE:-1}"
[ "$#" -ge 1 ] || { echo "usage: $0 DIR [DIR ...] (place-recognition datasets, or folders of them)"; exit 2; }
[ -x "$BIN/evaluate_places" ] || "$AP_ROOT/scripts/setup.sh" || exit 1
OUT="$AP_ROOT/results/places_traversals"
mkdir -p "$OUT"
has_images() { compgen -G "$1/*.[jJpPbB][pPnNmM][gGpP]" > /dev/null || compgen -G "$1/*.[jJ][pP][eE][gG]" > /dev/null; }
pair_of() {  # prints "REF QUERY" for a dataset folder, nothing otherwise
  local d="$1"
  if [ -d "$d/ref" ] && [ -d "$d/query" ]; then echo "$d/ref $d/query"; return; fi
  local subs=()
  for s in "$d"/*/; do s="${s%/}"; has_images "$s" && subs+=("$s"); done
  [ "${#subs[@]}" -eq 2 ] && echo "${subs[0]} ${subs[1]}"
}
datasets=()
for d in "$@"; do
  d="${d%/}"
  if [ -n "$(pair_of "$d")" ]; then datasets+=("$d"); continue; fi
  found=0
  for s in "$d"/*/; do
    s="${s%/}"
    if [ -n "$(pair_of "$s")" ]; then datasets+=("$s"); found=1; fi
  done
  [ "$found" -eq 1 ] || echo "evaluate_places_traversals: $d: no dataset (ref/ + query/, or two image folders) in it (skipped)"
done
[ "${#datasets[@]}" -gt 0 ] || { echo "evaluate_places_traversals: no dataset found"; exit 1; }

csv="$OUT/table.csv"
echo "dataset,reference,query,queries,tolerance_frames,method,recall_at_1,recall_at_5,pr_auc,recall_at_full_precision,match_ms" > "$csv"
for d in "${datasets[@]}"; do
  name="$(basename "$d")"
  read -r ref query <<< "$(pair_of "$d")"
  dir="$OUT/$name"
  mkdir -p "$dir"
  if ! "$BIN/evaluate_places" --reference "$ref" --query "$query" --tolerance_frames "$TOLERANCE" \
      --output "$dir" > "$dir/log.txt" 2>&1; then
    echo "evaluate_places_traversals: $name failed: $(tail -n 1 "$dir/log.txt")" >&2
    continue
  fi
  line="$(tail -n 1 "$dir/log.txt")"
  echo "$line"
  python3 "$AP_ROOT/scripts/plot_places.py" "$dir" "$name: $(basename "$query") against $(basename "$ref")" \
    || echo "evaluate_places_traversals: no plot for $name (python3-matplotlib?)" >&2
  # One row per method from the table evaluate_places printed.
  awk -v n="$name" -v r="$(basename "$ref")" -v q="$(basename "$query")" -v c="$(summary_value "$line" queries)" -v t="$TOLERANCE" \
    '/^  (thumbnail|gradient|chromaticity|layout|words|fused|sequence|route) /{print n","r","q","c","t","$1","$2","$3","$4","$5","$6}' \
    "$dir/log.txt" >> "$csv"
done
md="$OUT/table.md"
{
  md_header "dataset" "query against reference" "queries" "method" "recall@1" "recall@5" "PR AUC" "recall at 100% precision" "ms per query"
  tail -n +2 "$csv" | awk -F, '{printf "| %s | %s / %s | %s | %s | %s | %s | %s | %s | %s |\n", $1, $3, $2, $4, $6, $7, $8, $9, $10, $11}'
} > "$md"
cat "$md"
echo "evaluate_places_traversals: tolerance ${TOLERANCE} frames; table in $csv and $md, PR curves in $OUT/<dataset>/pr_curve.png"
