#!/usr/bin/env bash
# Memory check: nodes processing a long simulator bag must hold steady memory. Simulates
#   laser: DURATION_S seconds of the corridor loop (config/worlds/loop.yaml) through
#          line_extractor + ekf_slam_mapper (slam_demo-like: map -> odom from the truth), and
#   field: DURATION_S seconds of the switching field script through color_estimator + rbpf_localizer,
# plays each at RATE x, samples each node's resident memory (VmRSS, /proc) every second, and prints
#   memory: node=N rss_start_mb=A rss_end_mb=B peak_start_mb=C peak_end_mb=D growth_mb_per_h=G
# where "start" is the first tenth of the replay (after start-up allocations) and growth is the
# least-squares slope of RSS over the rest, per hour of bag time. Logs and samples in results/memory/.
# Usage: scripts/check_memory.sh [DURATION_S=1200] [RATE=10]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
DURATION="${1:-1200}"
RATE="${2:-10}"
OUT="$AP_ROOT/results/memory"
mkdir -p "$OUT"
use_workspace
TMP="$(mktemp -d)"
LAUNCH_PID=""
cleanup() { [ -n "$LAUNCH_PID" ] && kill "$LAUNCH_PID" 2> /dev/null; wait 2> /dev/null; rm -rf "$TMP"; }
trap cleanup EXIT

# sample NAME... : one line "t node rss_kb hwm_kb" per node per second while the launch runs.
sample() {
  local csv="$1"
  shift
  echo "t_s,node,rss_kb,hwm_kb" > "$csv"
  local t=0
  while kill -0 "$LAUNCH_PID" 2> /dev/null; do
    for n in "$@"; do
      local pid
      pid="$(pgrep -f "__name:=$n( |$)" | head -n 1 || true)"
      [ -z "$pid" ] && continue
      local rss hwm
      rss="$(awk '/^VmRSS/ {print $2}' "/proc/$pid/status" 2> /dev/null || true)"
      hwm="$(awk '/^VmHWM/ {print $2}' "/proc/$pid/status" 2> /dev/null || true)"
      [ -n "$rss" ] && echo "$t,$n,$rss,$hwm" >> "$csv"
    done
    sleep 1
    t=$((t + 1))
  done
}

report() {  # csv rate
  python3 - "$1" "$2" << 'EOF'
import csv, sys
rows = {}
for r in csv.DictReader(open(sys.argv[1])):
    rows.setdefault(r["node"], []).append((float(r["t_s"]), float(r["rss_kb"]) / 1024, float(r["hwm_kb"]) / 1024))
rate = float(sys.argv[2])
for node, v in rows.items():
    if len(v) < 20:
        print(f"memory: node={node} samples={len(v)} (too few)")
        continue
    k = max(1, len(v) // 10)
    start, rest = v[:k], v[k:]
    n = len(rest)
    mt = sum(t for t, _, _ in rest) / n
    mr = sum(r for _, r, _ in rest) / n
    slope = sum((t - mt) * (r - mr) for t, r, _ in rest) / max(1e-9, sum((t - mt) ** 2 for t, _, _ in rest))
    # wall seconds -> bag seconds: the bag plays RATE x faster
    print(f"memory: node={node} samples={len(v)} rss_start_mb={start[-1][1]:.1f} rss_end_mb={v[-1][1]:.1f} "
          f"peak_start_mb={start[-1][2]:.1f} peak_end_mb={v[-1][2]:.1f} "
          f"growth_mb_per_h={slope * 3600 / rate:.2f}")
EOF
}

# replay NAME LAUNCH NODE...: plays $TMP/NAME.bag through LAUNCH, sampling the NODEs, and reports.
replay() {
  local name="$1" launch="$2"
  shift 2
  roslaunch --disable-title adaptive_perception "$launch" bag:="$TMP/$name.bag" rate:="$RATE" \
    name:="memory_$name" > "$OUT/$name.log" 2>&1 &
  LAUNCH_PID=$!
  sample "$OUT/$name.csv" "$@"
  wait "$LAUNCH_PID" || true
  LAUNCH_PID=""
  report "$OUT/$name.csv" "$RATE" | tee -a "$OUT/summary.txt"
  rm -f "$TMP/$name.bag"
}
: > "$OUT/summary.txt"

# Laser: the corridor loop, lap after lap.
"$BIN/simulate_laser" --world "$AP_ROOT/config/worlds/loop.yaml" --duration_s "$DURATION" --seed 5 \
  --output "$TMP/laser.bag" > /dev/null
replay laser laser_demo.launch line_extractor ekf_slam_mapper

# Field: lights switching every 5 s, the robot walking the whole time.
"$BIN/simulate_field" --script switching --seed 9 --duration_s "$DURATION" --rate_hz 4 \
  --switch_period_s 5 --output "$TMP/field.bag" --overwrite > /dev/null
replay field field_demo.launch color_estimator rbpf_localizer
