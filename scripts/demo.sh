#!/usr/bin/env bash
# The demo: sets up (apt + build), then replays every bundled bag in rosbag/ through every node that
# exists, printing one summary line per bag. rviz opens when a display is present (or with rviz:=true);
# rviz:=false keeps it closed. Usage: scripts/demo.sh [rviz:=true|false] [rate:=R]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
RVIZ=false
[ -n "${DISPLAY:-}" ] && RVIZ=true
RATE=1.0
for a in "$@"; do
  case "$a" in
    rviz:=*) RVIZ="${a#rviz:=}" ;;
    rate:=*) RATE="${a#rate:=}" ;;
    *) echo "usage: $0 [rviz:=true|false] [rate:=R]" >&2; exit 2 ;;
  esac
done
"$AP_ROOT/scripts/setup.sh"
set +u; source "$AP_WS/devel/setup.bash"; set -u
export ROS_HOME="${ROS_HOME:-$AP_WS/ros_home}"
mkdir -p "$AP_ROOT/results/demo"
summary="$AP_ROOT/results/demo/summary.txt"
: > "$summary"
for bag in "$AP_ROOT"/rosbag/field_*.bag "$AP_ROOT"/rosbag/laser_*.bag; do
  name="$(basename "$bag" .bag)"
  launch=demo.launch
  case "$name" in laser_*) launch=laser_demo.launch ;; esac
  echo "demo: replaying $name through $launch (rviz=$RVIZ)"
  roslaunch --disable-title adaptive_perception "$launch" bag:="$bag" name:="$name" rviz:="$RVIZ" \
    rate:="$RATE" > "$AP_ROOT/results/demo/$name.log" 2>&1 || true
  line="$(grep -h '^demo_monitor:' "$AP_ROOT/results/demo/$name.log" | tail -n 1)"
  if [ -z "$line" ]; then
    echo "demo: $name produced no summary; see results/demo/$name.log"; tail -n 20 "$AP_ROOT/results/demo/$name.log"; exit 1
  fi
  echo "$line" | tee -a "$summary"
done
echo "demo: summaries in results/demo/summary.txt, logs beside it"
