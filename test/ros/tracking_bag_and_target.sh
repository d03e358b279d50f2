#!/usr/bin/env bash
# For hostile_condensation_tracker.test (the harness's bag_command): simulates a tracking sequence
# (scenario $1, seed 1, $2 frames) as the bag $BAG and gives condensation_tracker its first true box
# through the set_target service, so the tracker starts on the bag's first image.
set -euo pipefail
SCENARIO="${1:-distractor}"
FRAMES="${2:-150}"
: "${BAG:?BAG must name the bag to write}"
rosrun adaptive_perception simulate_tracking --scenario "$SCENARIO" --seed 1 --frames "$FRAMES" \
  --output "$BAG"
rosrun adaptive_perception simulate_tracking --scenario "$SCENARIO" --seed 1 --frames 1 \
  --video "${BAG%.bag}_first.avi"
IFS=, read -r _ X Y W H < <(sed -n 2p "${BAG%.bag}_first.csv")
rosservice call /condensation_tracker/set_target \
  "roi: {x_offset: ${X%.*}, y_offset: ${Y%.*}, width: ${W%.*}, height: ${H%.*}, do_rectify: false}"
