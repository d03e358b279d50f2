#!/usr/bin/env bash
# The relations benchmark (Kuemmerle et al. 2009) on every real log in data/laser/ (a log without a
# relations file, such as fr-clinic, is mapped and timed but not scored): carmen_to_bag with its
# defaults, then
# evaluate_slam with its defaults (slam::LaserSlam's: the laser-odometry front end and loop closing),
# the same on every log (FLAGS adds options), and one table of relation errors (mean and std, translational and rotational)
# beside the published figures of the usual peers, plus each log's map PNG. Writes
# results/slam_benchmark/<log>/ (evaluate_slam's output, log.txt), table.csv and table.md.
# Usage: [FLAGS="..."] scripts/evaluate_slam_benchmark.sh [--leave_one_out] [LOG ...]
# About 10 minutes on two cores for the four logs.
# --leave_one_out: also the defaults chosen without each log. The one default set on these logs'
# relations is the EKF's prediction noise behind the front end (LaserSlamConfig::front_end_motion,
# a quarter of the wheel-odometry model); every log with relations is run again with it scaled by
# each of LOO_SCALES (--odom_noise_scale), and each log is then scored with the scale that does best
# on the OTHER logs (the mean of their errors, each relative to its error at the default). Prints
# that table beside the defaults' and writes leave_one_out.csv / .md. About 3 times as long.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
FLAGS="${FLAGS:-}"
LOO=0
if [ "${1:-}" = "--leave_one_out" ]; then LOO=1; shift; fi
LOO_SCALES="${LOO_SCALES:-0.5 2 4}"
[ -x "$BIN/evaluate_slam" ] || "$AP_ROOT/scripts/setup.sh" || exit 1
OUT="$AP_ROOT/results/slam_benchmark"
mkdir -p "$OUT"
logs=("$@")
if [ "${#logs[@]}" -eq 0 ]; then
  for r in "$AP_ROOT"/data/laser/*.clf.bz2; do logs+=("$(basename "$r" .clf.bz2)"); done
fi
# Published mean translational relation errors (m): scan matching, GMapping, graph mapping
# (Kuemmerle et al. 2009, Table 1), Cartographer (Hess et al., ICRA 2016, Table 3).
published() {
  case "$1" in
    intel) echo "0.220 0.070 0.031 0.0229" ;;
    fr079) echo "0.258 0.061 0.056 0.0452" ;;
    mit-csail) echo "0.106 0.049 0.004 0.0319" ;;
    *) echo "- - - -" ;;
  esac
}
csv="$OUT/table.csv"
loo_runs="$OUT/leave_one_out_runs.csv"
[ "$LOO" = 1 ] && echo "log,odom_noise_scale,trans_error_m" > "$loo_runs"
echo "log,scans,relations_used,trans_error_m,trans_error_m_std,rot_error_deg,rot_error_deg_std,ekf_trans_error_m,front_end_trans_error_m,loop_closures,realtime_factor,published_scan_matching_m,published_gmapping_m,published_graph_mapping_m,published_cartographer_m" > "$csv"
for log in "${logs[@]}"; do
  dir="$OUT/$log"
  mkdir -p "$dir"
  rel="$AP_ROOT/data/laser/relations/$log.relations"
  rel_args=()
  if [ -f "$rel" ]; then rel_args=(--relations "$rel"); else
    echo "evaluate_slam_benchmark: no relations for $log: mapped, not scored (judge its map_grid.png)"; fi
  "$BIN/carmen_to_bag" --input "$AP_ROOT/data/laser/$log.clf.bz2" --output "$dir/$log.bag" \
    --overwrite --max_issues 3 > "$dir/log.txt" 2>&1 || {
    echo "evaluate_slam_benchmark: $log: carmen_to_bag failed: $(tail -n 1 "$dir/log.txt")"; continue; }
  # shellcheck disable=SC2086
  if ! "$BIN/evaluate_slam" --bag "$dir/$log.bag" "${rel_args[@]}" $FLAGS --output "$dir" \
      --name "$log" >> "$dir/log.txt" 2>&1; then
    echo "evaluate_slam_benchmark: $log: evaluate_slam failed: $(tail -n 1 "$dir/log.txt")"; continue
  fi
  line="$(grep '^evaluate_slam:' "$dir/log.txt" | tail -n 1)"
  echo "$log $line"
  v() { summary_value "$line" "$1"; }
  if [ "$LOO" = 1 ] && [ -f "$rel" ]; then
    echo "$log,1,$(v relation_trans_error_m)" >> "$loo_runs"
    for scale in $LOO_SCALES; do
      sdir="$dir/odom_noise_scale_$scale"
      mkdir -p "$sdir"
      # shellcheck disable=SC2086
      if "$BIN/evaluate_slam" --bag "$dir/$log.bag" "${rel_args[@]}" $FLAGS --odom_noise_scale \
          "$scale" --output "$sdir" --name "$log" > "$sdir/log.txt" 2>&1; then
        sline="$(grep '^evaluate_slam:' "$sdir/log.txt" | tail -n 1)"
        serr="$(summary_value "$sline" relation_trans_error_m)"
        # Only a run that scored: a missing or non-positive error is never chosen.
        if awk -v e="$serr" 'BEGIN { exit !(e + 0 > 0) }'; then
          echo "$log,$scale,$serr" >> "$loo_runs"
        else
          echo "evaluate_slam_benchmark: $log at --odom_noise_scale $scale: no relation error"
        fi
        echo "$log odom_noise_scale=$scale $sline"
      else
        echo "evaluate_slam_benchmark: $log at --odom_noise_scale $scale failed: $(tail -n 1 "$sdir/log.txt")"
      fi
    done
  fi
  rm -f "$dir/$log.bag"
  read -r p_sm p_gm p_graph p_carto <<< "$(published "$log")"
  echo "$log,$(v scans),$(v relations_used),$(v relation_trans_error_m),$(v relation_trans_error_m_std),$(v relation_rot_error_deg),$(v relation_rot_error_deg_std),$(v ekf_relation_trans_error_m),$(v front_end_relation_trans_error_m),$(v loop_closures),$(v realtime_factor),$p_sm,$p_gm,$p_graph,$p_carto" >> "$csv"
done
md="$OUT/table.md"
{
  md_header "log" "scans" "relations" "translational error (m)" "std" "rotational error (deg)" "std" "EKF before loop closing (m)" "front end alone (m)" "loop closures" "x real time" "published: scan matching" "GMapping" "graph mapping" "Cartographer"
  tail -n +2 "$csv" | awk -F, '{printf "| %s |", $1; for (i = 2; i <= NF; ++i) { v = $i; if (v ~ /^-1(\.0+)?$/) v = "-"; printf " %s |", v } printf "\n"}'
} > "$md"
cat "$md"
echo "evaluate_slam_benchmark: flags '${FLAGS:-(the defaults)}'; table in $csv and $md, maps in $OUT/<log>/: map.png (line landmarks), map_grid.png and map.yaml + map.pgm (the occupancy grid at the optimised poses, map_server format)"
[ "$LOO" = 1 ] || exit 0
# Each log with relations, scored at the scale chosen on the others (ties go to the default, 1).
loo_csv="$OUT/leave_one_out.csv"
awk -F, 'NR > 1 { e[$1, $2] = $3; logs[$1] = 1; scales[$2] = 1 }
  END {
    print "log,trans_error_m_defaults,odom_noise_scale_chosen_without_it,trans_error_m_leave_one_out"
    for (l in logs) {
      best = 1; best_score = -1
      for (s in scales) {
        sum = 0; n = 0; ok = 1
        for (m in logs) {
          if (m == l) continue
          if (!((m, s) in e) || !((m, 1) in e) || e[m, 1] <= 0 || e[m, s] <= 0) { ok = 0; break }
          sum += e[m, s] / e[m, 1]; ++n
        }
        if (!ok || n == 0) continue
        score = sum / n
        if (best_score < 0 || score < best_score - 1e-12 || (score <= best_score + 1e-12 && s == 1)) {
          best = s; best_score = score
        }
      }
      printf "%s,%s,%s,%s\n", l, e[l, 1], best, ((l, best) in e) ? e[l, best] : "-"
    }
  }' "$loo_runs" | { read -r header; echo "$header"; sort; } > "$loo_csv"
loo_md="$OUT/leave_one_out.md"
{
  md_header "log" "translational error, defaults (m)" "odom_noise_scale chosen without the log" "translational error, leave one log out (m)"
  tail -n +2 "$loo_csv" | awk -F, '{printf "| %s | %s | %s | %s |\n", $1, $2, $3, $4}'
} > "$loo_md"
cat "$loo_md"
echo "evaluate_slam_benchmark: leave one log out over --odom_noise_scale 1 $LOO_SCALES: $loo_csv and $loo_md (every run: $loo_runs)"
