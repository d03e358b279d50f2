#!/usr/bin/env bash
# rostest helper for rbpf_localizer_kidnap.test: simulates the kidnap sequence of
# scripts/evaluate_localization.sh (simulate_field --script kidnap --seed 4, 20 s at 4 Hz: the
# robot is teleported at 10 s to a free pose at least 1.5 m away) and plays it with --clock at
# RATE. Fixed seeds: the same bag every run.
# Usage (as a launch node): kidnap_bag_player.sh RATE [roslaunch's __name:= / __log:= args]
set -euo pipefail
RATE="${1:-0.5}"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
rosrun adaptive_perception simulate_field --script kidnap --seed 4 --duration_s 20 --rate_hz 4 \
  --output "$OUT/kidnap.bag" > /dev/null
sleep 2  # the localizer subscribes
rosbag play --clock --quiet --rate "$RATE" "$OUT/kidnap.bag"
