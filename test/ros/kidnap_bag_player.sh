#!/usr/bin/env bash
# rostest helper for rbpf_localizer_kidnap.test: simulates the kidnap sequence of
# scripts/evaluate_localization.sh (simulate_field --script kidnap --seed 4, 20 s at 4 Hz: the
# robot is teleported at 10 s to a free pose at least 1.5 m away) and plays it with /clock in step
# with rbpf_localizer. Fixed seeds: the same bag every run.
# Usage (as a launch node): kidnap_bag_player.sh [roslaunch's __name:= / __log:= args]
set -euo pipefail
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
rosrun adaptive_perception simulate_field --script kidnap --seed 4 --duration_s 20 --rate_hz 4 \
  --output "$OUT/kidnap.bag" > /dev/null
# In step with the localizer (src/tools/lockstep_player.cpp): each image waits for the pose of the
# one before, so the result does not depend on how many frames a loaded machine lets it keep up
# with.
rosrun adaptive_perception lockstep_player "$OUT/kidnap.bag" _trigger_topic:=camera/image_raw \
  _output_topic:=rbpf_localizer/pose _delay_s:=2
