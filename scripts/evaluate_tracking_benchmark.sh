#!/usr/bin/env bash
# Runs evaluate_tracking over every benchmark sequence (OTB or VOT folder) found in the folders
# given, with the default tracker and its peers side by side (OpenCV CSRT, KCF, CamShift, from the
# same first box on the same frames), and the paper's CONDENSATION and the ellipse tracker alone.
# A folder given may be a sequence itself or hold sequences. Writes results/tracking_benchmark/:
#   <sequence>/<tracker>/   each run (frames.csv, curves.csv, results.yaml, strip.png)
#   <sequence>.png          its success and precision plots (scripts/plot_tracking.py)
#   all.png                 the plots averaged over the sequences (each weighs the same)
#   table.csv, table.md     one row per sequence and the mean: success rate, AUC, precision@20px
#                           and frames/s of each tracker
# and prints each run's summary line and the Markdown table. The benchmarks' frames stay where they
# are (research-use terms: never copied into the project).
# Usage: scripts/evaluate_tracking_benchmark.sh DIR [DIR ...]
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
[ "$#" -ge 1 ] || { echo "usage: $0 DIR [DIR ...] (OTB / VOT sequence folders, or folders of them)"; exit 2; }
[ -x "$BIN/evaluate_tracking" ] || "$AP_ROOT/scripts/setup.sh" || exit 1
OUT="$AP_ROOT/results/tracking_benchmark"
mkdir -p "$OUT"
is_sequence() { [ -f "$1/groundtruth_rect.txt" ] || [ -f "$1/groundtruth_rect.1.txt" ] || [ -f "$1/groundtruth.txt" ]; }
sequences=()
for d in "$@"; do
  d="${d%/}"
  if is_sequence "$d"; then sequences+=("$d"); continue; fi
  found=0
  for s in "$d"/*/; do
    s="${s%/}"
    if is_sequence "$s"; then sequences+=("$s"); found=1; fi
  done
  [ "$found" -eq 1 ] || echo "evaluate_tracking_benchmark: $d: no OTB or VOT sequence in it (skipped)"
done
[ "${#sequences[@]}" -gt 0 ] || { echo "evaluate_tracking_benchmark: no sequence found"; exit 1; }

csv="$OUT/table.csv"
cols="ours_success_rate,ours_auc,ours_precision_20px,ours_fps,condensation_success_rate,condensation_auc,ellipse_success_rate,ellipse_auc,csrt_success_rate,csrt_auc,csrt_precision_20px,csrt_fps,kcf_success_rate,kcf_auc,kcf_precision_20px,kcf_fps,camshift_success_rate,camshift_auc,camshift_precision_20px"
echo "sequence,frames,$cols" > "$csv"
run() {  # sequence-dir out-dir args...
  local seq="$1" dir="$2"
  shift 2
  mkdir -p "$dir"
  if ! "$BIN/evaluate_tracking" --sequence "$seq" --output "$dir" "$@" > "$dir/log.txt" 2>&1; then
    echo "evaluate_tracking_benchmark: $seq $* failed: $(tail -n 1 "$dir/log.txt")" >&2
    return 1
  fi
  grep '^evaluate_tracking:' "$dir/log.txt" | tail -n 1
}
ok_runs=()
for seq in "${sequences[@]}"; do
  name="$(basename "$seq")"
  main="$(run "$seq" "$OUT/$name/box")" || continue
  cond="$(run "$seq" "$OUT/$name/condensation" --mode condensation --peers none)" || cond=""
  ell="$(run "$seq" "$OUT/$name/ellipse" --mode ellipse --peers none)" || ell=""
  echo "$main"
  grep '^evaluate_tracking: note:' "$OUT/$name/box/log.txt" || true
  v() { summary_value "$1" "$2"; }
  row="$name,$(v "$main" frames)"
  for k in success_rate auc precision_20px fps; do row="$row,$(v "$main" "$k")"; done
  row="$row,$(v "$cond" success_rate),$(v "$cond" auc),$(v "$ell" success_rate),$(v "$ell" auc)"
  for p in csrt kcf; do
    for k in success_rate auc precision_20px fps; do row="$row,$(v "$main" "${p}_$k")"; done
  done
  for k in success_rate auc precision_20px; do row="$row,$(v "$main" "camshift_$k")"; done
  echo "$row" >> "$csv"
  python3 "$AP_ROOT/scripts/plot_tracking.py" "$OUT/$name.png" "$name" "$OUT/$name/box" || true
  ok_runs+=("$OUT/$name/box")
done
[ "${#ok_runs[@]}" -gt 0 ] || { echo "evaluate_tracking_benchmark: every run failed"; exit 1; }
python3 "$AP_ROOT/scripts/plot_tracking.py" "$OUT/all.png" "mean over the sequences" "${ok_runs[@]}" || true
# The mean row and the Markdown table.
python3 - "$csv" "$OUT/table.md" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
keys = [k for k in rows[0] if k not in ("sequence", "frames")]
def num(x):
    try:
        return float(x)
    except ValueError:
        return math.nan
mean = {k: sum(num(r[k]) for r in rows) / len(rows) for k in keys}
with open(sys.argv[1], "a") as f:
    f.write("mean of %d,%d,%s\n" % (len(rows), sum(int(num(r["frames"])) for r in rows),
                                   ",".join("%.3f" % mean[k] for k in keys)))
head = ["sequence", "frames", "ours success / AUC / P@20 / fps", "CONDENSATION (paper)", "ellipse",
        "CSRT success / AUC / P@20 / fps", "KCF success / AUC / P@20 / fps", "CamShift success / AUC / P@20"]
def cell(r, p, ks):
    return " / ".join(("%.3f" % num(r[p + k]) if not k.endswith("fps") else "%.0f" % num(r[p + k])) for k in ks)
full = ["_success_rate", "_auc", "_precision_20px", "_fps"]
lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
for r in rows + [dict(mean, sequence="**mean of %d**" % len(rows), frames=str(sum(int(num(x["frames"])) for x in rows)))]:
    lines.append("| " + " | ".join([r["sequence"], r["frames"], cell(r, "ours", full),
                                   cell(r, "condensation", full[:2]), cell(r, "ellipse", full[:2]),
                                   cell(r, "csrt", full), cell(r, "kcf", full),
                                   cell(r, "camshift", full[:3])]) + " |")
open(sys.argv[2], "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
echo "evaluate_tracking_benchmark: table in $csv and $OUT/table.md, plots in $OUT/*.png"
