#!/usr/bin/env bash
# The demo: sets up (apt + build), replays every bundled bag in rosbag/ through the nodes (field bags:
# color_estimator + rbpf_localizer; laser bags and the Intel lab's real log: line_extractor +
# ekf_slam_mapper; simulated indoor runs:
# histogram_place_recognizer and appearance_localizer; a simulated tracking sequence:
# condensation_tracker), printing one summary line per run, then plays the field, laser-loop, building
# and tracking runs all at once through launch/demo.launch (its data stays in results/demo/all, so
# `roslaunch adaptive_perception demo.launch rviz:=true` can replay it), then runs a short version of
# every paper's experiment and writes results/REPORT.md (scripts/make_report.sh; report:=false skips it).
# rviz opens when a display is present (or with rviz:=true); rviz:=false keeps it closed.
# Usage: scripts/demo.sh [rviz:=true|false] [rate:=R] [report:=true|false]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
RVIZ=false
[ -n "${DISPLAY:-}" ] && RVIZ=true
RATE=1.0
REPORT=true
for a in "$@"; do
  case "$a" in
    rviz:=*) RVIZ="${a#rviz:=}" ;;
    rate:=*) RATE="${a#rate:=}" ;;
    report:=*) REPORT="${a#report:=}" ;;
    *) echo "usage: $0 [rviz:=true|false] [rate:=R] [report:=true|false]" >&2; exit 2 ;;
  esac
done
"$AP_ROOT/scripts/setup.sh"
use_workspace
mkdir -p "$AP_ROOT/results/demo"
summary="$AP_ROOT/results/demo/summary.txt"
: > "$summary"
for bag in "$AP_ROOT"/rosbag/field_*.bag "$AP_ROOT"/rosbag/laser_*.bag; do
  name="$(basename "$bag" .bag)"
  # Field bags play in step with the localizer (field_demo.launch lockstep:=true): it takes every
  # image on any machine, so the localizer's figures do not depend on the machine's speed.
  launch=field_demo.launch
  extra=(lockstep:=true)
  case "$name" in laser_*) launch=laser_demo.launch; extra=() ;; esac
  echo "demo: replaying $name through $launch (rviz=$RVIZ)"
  roslaunch --disable-title adaptive_perception "$launch" bag:="$bag" name:="$name" rviz:="$RVIZ" \
    rate:="$RATE" "${extra[@]}" > "$AP_ROOT/results/demo/$name.log" 2>&1 || true
  line="$(grep -h '^demo_monitor:' "$AP_ROOT/results/demo/$name.log" | tail -n 1)"
  if [ -z "$line" ]; then
    echo "demo: $name produced no summary; see results/demo/$name.log"; tail -n 20 "$AP_ROOT/results/demo/$name.log"; exit 1
  fi
  echo "$line" | tee -a "$summary"
done
# A real laser log: the Intel lab (CARMEN, 45 minutes, no ground truth) converted with the scans' own
# odometry and replayed 20x faster through line_extractor + ekf_slam_mapper (which then owns map -> odom).
real_bag="$AP_ROOT/results/demo/intel.bag"
"$AP_WS/devel/lib/adaptive_perception/carmen_to_bag" --input "$AP_ROOT/data/laser/intel.clf.bz2" \
  --output "$real_bag" --overwrite --max_issues 0 > /dev/null 2>&1
echo "demo: replaying intel (real log) through laser_demo.launch (rviz=$RVIZ)"
rrate="$(awk -v r="$RATE" 'BEGIN { print 20 * r }')"
roslaunch --disable-title adaptive_perception laser_demo.launch bag:="$real_bag" name:=intel real_log:=true \
  rviz:="$RVIZ" rate:="$rrate" > "$AP_ROOT/results/demo/intel.log" 2>&1 || true
rm -f "$real_bag"
line="$(grep -h '^demo_monitor:' "$AP_ROOT/results/demo/intel.log" | tail -n 1)"
if [ -z "$line" ]; then
  echo "demo: intel produced no summary; see results/demo/intel.log"; tail -n 20 "$AP_ROOT/results/demo/intel.log"; exit 1
fi
echo "$line" | tee -a "$summary"
# Place recognition: the indoor simulator makes a training run and a test run of the building
# (cloudy, seeds 1 and 2, 1 Hz, 160 x 120; deterministic, ~30 MB each, kept out of the repository),
# train_places builds the database, and the test run is replayed through histogram_place_recognizer.
places_dir="$AP_ROOT/results/demo/places"
mkdir -p "$places_dir"
for run in train:1 test:2; do
  "$BIN/simulate_indoor" --lighting cloudy --seed "${run#*:}" --camera_rate_hz 1 --width_px 160 --height_px 120 \
    --output "$places_dir/${run%%:*}.bag" --overwrite > /dev/null 2>&1
done
rm -f "$places_dir/places.sqlite"
"$BIN/train_places" --bag "$places_dir/train.bag" --database "$places_dir/places.sqlite" > /dev/null 2>&1
echo "demo: replaying indoor_places through places_demo.launch (rviz=$RVIZ)"
prate="$(awk -v r="$RATE" 'BEGIN { print 10 * r }')"
roslaunch --disable-title adaptive_perception places_demo.launch bag:="$places_dir/test.bag" \
  database:="$places_dir/places.sqlite" rviz:="$RVIZ" rate:="$prate" > "$AP_ROOT/results/demo/indoor_places.log" 2>&1 || true
line="$(grep -h '^histogram_place_recognizer: images=' "$AP_ROOT/results/demo/indoor_places.log" | tail -n 1)"
if [ -z "$line" ]; then
  echo "demo: indoor_places produced no summary; see results/demo/indoor_places.log"; tail -n 20 "$AP_ROOT/results/demo/indoor_places.log"; exit 1
fi
echo "indoor_places $line" | tee -a "$summary"
rm -f "$places_dir/train.bag" "$places_dir/test.bag"
# Rooms: a SIFT database of one run of the building (309 x 240, cloudy, seed 1) and another run
# (seed 2) replayed through appearance_localizer (room classification and appearance MCL).
for run in train:1 test:2; do
  "$BIN/simulate_indoor" --lighting cloudy --seed "${run#*:}" --camera_rate_hz 1 \
    --output "$places_dir/rooms_${run%%:*}.bag" --overwrite > /dev/null 2>&1
done
rm -f "$places_dir/rooms.sqlite"
"$BIN/train_places" --bag "$places_dir/rooms_train.bag" --database "$places_dir/rooms.sqlite" \
  --images_per_place 0 --features --spaces hsv > /dev/null 2>&1
demo_part() {  # NAME LAUNCH ARGS...: replays through LAUNCH, prints demo_monitor's line
  local name="$1" launch="$2"
  shift 2
  echo "demo: replaying $name through $launch (rviz=$RVIZ)"
  roslaunch --disable-title adaptive_perception "$launch" name:="$name" rviz:="$RVIZ" "$@" \
    > "$AP_ROOT/results/demo/$name.log" 2>&1 || true
  local line
  line="$(grep -h '^demo_monitor:' "$AP_ROOT/results/demo/$name.log" | tail -n 1)"
  if [ -z "$line" ]; then
    echo "demo: $name produced no summary; see results/demo/$name.log"; tail -n 20 "$AP_ROOT/results/demo/$name.log"; exit 1
  fi
  echo "$line" | tee -a "$summary"
}
demo_part indoor_rooms rooms_demo.launch bag:="$places_dir/rooms_test.bag" \
  database:="$places_dir/rooms.sqlite" rate:="$prate"
# The data of the all-at-once demo (launch/demo.launch): each run moved into its own namespace and
# frames (scripts/prefix_bag.py), all starting at the field bags' stamp.
all_dir="$AP_ROOT/results/demo/all"
mkdir -p "$all_dir"
T0=1600000000
PY=/usr/bin/python3
$PY "$AP_ROOT/scripts/prefix_bag.py" --prefix rooms --start_s $T0 --duration_s 120 "$places_dir/rooms_test.bag" \
  "$all_dir/rooms.bag" > /dev/null
rm -f "$all_dir/places.sqlite" "$all_dir/rooms.sqlite"
"$BIN/train_places" --bag "$places_dir/rooms_train.bag" --database "$all_dir/places.sqlite" > /dev/null 2>&1
cp "$places_dir/rooms.sqlite" "$all_dir/rooms.sqlite"
rm -f "$places_dir/rooms_train.bag" "$places_dir/rooms_test.bag"
$PY "$AP_ROOT/scripts/prefix_bag.py" --prefix slam --start_s $T0 "$AP_ROOT/rosbag/laser_loop.bag" \
  "$all_dir/slam.bag" > /dev/null
"$BIN/simulate_field" --script switching --seed 3 --duration_s 120 --rate_hz 4 --switch_period_s 2.5 \
  --output "$all_dir/field.bag" --overwrite > /dev/null
# Tracking: the distractor sequence (a second object of the target's colour crosses it), the tracker
# started on the first true box.
track_dir="$AP_ROOT/results/demo/tracking"
mkdir -p "$track_dir"
"$BIN/simulate_tracking" --scenario distractor --seed 1 --output "$track_dir/distractor.bag" \
  --overwrite > /dev/null
"$BIN/simulate_tracking" --scenario distractor --seed 1 --frames 1 --overwrite \
  --video "$track_dir/first.avi" > /dev/null
IFS=, read -r _ x y w h < <(sed -n 2p "$track_dir/first.csv")
demo_part tracking_distractor tracking_demo.launch bag:="$track_dir/distractor.bag" \
  initial_roi:="[$x, $y, $w, $h]" rate:="$RATE"
# For the all-at-once demo, the distractor scene over 2 minutes at 10 Hz (the same start box).
"$BIN/simulate_tracking" --scenario distractor --seed 1 --frames 1200 --rate_hz 10 \
  --output "$track_dir/long.bag" --overwrite > /dev/null
"$BIN/simulate_tracking" --scenario distractor --seed 1 --frames 1200 --rate_hz 10 --overwrite \
  --video "$track_dir/long.avi" > /dev/null
IFS=, read -r _ x y w h < <(sed -n 2p "$track_dir/long.csv")
$PY "$AP_ROOT/scripts/prefix_bag.py" --prefix tracking --start_s $T0 "$track_dir/long.bag" \
  "$all_dir/tracking.bag" > /dev/null
rm -f "$track_dir/long.bag" "$track_dir/long.avi"
echo "initial_roi: [$x, $y, $w, $h]" > "$all_dir/initial_roi.yaml"
# Everything at once, as `roslaunch adaptive_perception demo.launch rviz:=true` shows it: one line per part.
echo "demo: replaying the field, laser loop, building and tracking runs at once through demo.launch (rviz=$RVIZ)"
roslaunch --disable-title adaptive_perception demo.launch rviz:="$RVIZ" rate:="$RATE" \
  > "$AP_ROOT/results/demo/all.log" 2>&1 || true
lines="$(grep -h '^demo_monitor: bag=all_' "$AP_ROOT/results/demo/all.log" || true)"
places_line="$(grep -h '^histogram_place_recognizer: images=' "$AP_ROOT/results/demo/all.log" | tail -n 1 || true)"
if [ "$(echo "$lines" | grep -c .)" -ne 4 ]; then
  echo "demo: demo.launch did not report all four parts; see results/demo/all.log"; tail -n 20 "$AP_ROOT/results/demo/all.log"; exit 1
fi
echo "$lines" | tee -a "$summary"
[ -n "$places_line" ] && echo "all_indoor_places $places_line" | tee -a "$summary"
echo "demo: summaries in results/demo/summary.txt, logs beside it"
if [ "$REPORT" = true ]; then
  echo "demo: running the papers' experiments for results/REPORT.md (about 10 minutes)"
  "$AP_ROOT/scripts/make_report.sh"
fi
