#!/usr/bin/env bash
# Runs the line extractor over the four real CARMEN logs in data/laser/: converts each with carmen_to_bag,
# then evaluate_lines (speed, segments per scan, one scan drawn as PNG) and evaluate_slam over the whole
# log (landmark map over the trajectory as PNG, landmark count, real-time factor). Writes results/real_logs/.
# Usage: scripts/evaluate_real_logs.sh [RETIRE_AFTER=0] [ODOM_NOISE_SCALE=1] [LOGS="intel fr079 mit-csail fr-clinic_robotlaser"]
# Odometry: the robot pose each laser line carries (carmen_to_bag's default). evaluate_slam runs with
# its defaults (slam::LaserSlam: laser-odometry front end, loop closing); ODOM_NOISE_SCALE scales the
# EKF's prediction noise. Retirement (the paper's 50 on USC SAL) is off by default: on the Intel log
# it froze landmarks before the loops closed (doubled corridors).
# Needs a built workspace (scripts/setup.sh). The whole set takes about 15 minutes on two cores.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
OUT="$AP_ROOT/results/real_logs"
RETIRE_AFTER="${1:-0}"
ODOM_NOISE_SCALE="${2:-1}"
LOGS="${3:-intel fr079 mit-csail fr-clinic_robotlaser}"
mkdir -p "$OUT"
summary="$OUT/summary.txt"
: > "$summary"
for log in $LOGS; do
  "$BIN/carmen_to_bag" --input "$AP_ROOT/data/laser/$log.clf.bz2" --output "$OUT/$log.bag" --overwrite --max_issues 3 \
    2> "$OUT/$log.issues.txt" | tee -a "$summary"
  "$BIN/evaluate_lines" --bag "$OUT/$log.bag" --output "$OUT/$log" --name "$log" | tail -n 1 | sed "s/^/$log /" | tee -a "$summary"
  "$BIN/evaluate_slam" --bag "$OUT/$log.bag" --retire_after_updates "$RETIRE_AFTER" \
    --odom_noise_scale "$ODOM_NOISE_SCALE" --output "$OUT/$log/slam" \
    --name "$log (retire after $RETIRE_AFTER)" | tail -n 1 | sed "s/^/$log /" | tee -a "$summary"
  rm -f "$OUT/$log.bag"
done
echo "evaluate_real_logs: plots in $OUT/<log>/scan.png and $OUT/<log>/slam/map.png, summary in $summary"
