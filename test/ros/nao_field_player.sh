#!/usr/bin/env bash
# rostest helper for nao_field_replay.test: makes a bag of one point of the NAO field development
# set (scripts/nao_field_list.py for the session, that point's line, field_images_to_bag with the
# NAO's top camera: SECONDS of the standing robot's image at 30 Hz) in a temporary folder, and plays
# it in step with rbpf_localizer (lockstep_player). The images stay where they are: nothing of the
# data set is copied into the project. IMU true: the bag has imu (the torso's pitch, from the list's
# torso_pitch_rad); false: the list's first five columns only, no imu.
# Usage (as a launch node): nao_field_player.sh SESSION_DIR POINT SECONDS IMU [roslaunch's args]
set -euo pipefail
SESSION="$1" POINT="$2" SECONDS_PER_IMAGE="$3" IMU="$4"
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT
PKG="$(rospack find adaptive_perception)"
python3 "$PKG/scripts/nao_field_list.py" "$SESSION" "$OUT/all.csv" top
columns=1-6
[ "${IMU,,}" = true ] || columns=1-5
{ head -n 1 "$OUT/all.csv"; grep "/$POINT/" "$OUT/all.csv"; } | cut -d, -f"$columns" > "$OUT/point.csv"
rosrun adaptive_perception field_images_to_bag --list "$OUT/point.csv" \
  --camera config/cameras/nao_v6_top.yaml --seconds_per_image "$SECONDS_PER_IMAGE" \
  --output "$OUT/point.bag"
rosrun adaptive_perception lockstep_player "$OUT/point.bag" \
  _trigger_topic:=camera/image_raw/compressed _output_topic:=rbpf_localizer/pose \
  _lookahead_s:=0.02 _delay_s:=4.0
