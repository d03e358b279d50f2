#!/usr/bin/env bash
# The results report: runs a short version of every paper's experiment with the project's own
# evaluate_* and bench_* tools, then writes results/REPORT.md (scripts/make_report.py) with the
# project's figures beside the papers' published ones and the plots embedded.
# Called by demo.sh after the node replays; needs a built workspace.
# Usage: scripts/make_report.sh [--output DIR]   (default results/report; REPORT.md goes beside DIR)
#
# Every part prints one line `report: part=NAME seconds=S <the tool's summary>` and appends it to
# DIR/summary.txt, which make_report.py reads. The full-size experiments are the evaluate_*.sh
# scripts the report names; the short ones here take about 10 minutes on two cores.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
OUT="$AP_ROOT/results/report"
[ "${1:-}" = "--output" ] && OUT="$2"
mkdir -p "$OUT"
cd "$AP_ROOT"
make_tmp
summary="$OUT/summary.txt"
: > "$summary"

# part NAME COMMAND...: runs COMMAND with its output in DIR/NAME.log and records its last summary
# line (`tool: key=value ...`).
part() {
  local name="$1"
  shift
  local start=$SECONDS
  if ! "$@" > "$OUT/$name.log" 2>&1; then
    echo "report: part=$name failed (see $OUT/$name.log)" | tee -a "$summary"
    return 0
  fi
  local line
  line="$(grep -E '^[a-z_]+: ([a-z_0-9]+=)' "$OUT/$name.log" | tail -n 1)"
  echo "report: part=$name seconds=$((SECONDS - start)) ${line#*: }" | tee -a "$summary"
}

# Colour paper (papers/000): Table 1 top rows with known poses, Fig. 6 (60 s, lights every 5 s).
for b in dark bright; do
  part "color_table1_$b" "$BIN/evaluate_color_estimation" --bag "rosbag/field_$b.bag" \
    --unknown_mahalanobis 1e9 --output "$OUT/color_table1_$b"
done
"$BIN/simulate_field" --script switching --seed 7 --duration_s 60 --rate_hz 4 --switch_period_s 5 \
  --output "$TMP/switching_60s.bag" --overwrite > /dev/null
for f in switching single; do
  part "color_fig6_$f" "$BIN/evaluate_color_estimation" --bag "$TMP/switching_60s.bag" --filter "$f" \
    --output "$OUT/color_fig6_$f" --no_plot
done
python3 scripts/plot_color_rates.py "switching filter=$OUT/color_fig6_switching/frames.csv" \
  "single Kalman filter=$OUT/color_fig6_single/frames.csv" "$OUT/color_fig6.png" \
  "Fig. 6: lights switched every 5 s" > /dev/null

# Localization (papers/000 section V): global start on the switching bag, both filters.
for f in switching single; do
  part "localization_$f" "$BIN/evaluate_localization" --bag rosbag/field_switching.bag --filter "$f" \
    --particles 500 --output "$OUT/localization_$f"
done
python3 scripts/plot_localization.py "$OUT/localization_switching" config/field_4legged.yaml \
  "rbpf_localizer, switching bag, global start" > /dev/null 2>&1 || true
# Every field bag with the switching filter: a global start (seed 1) and tracking from the true start.
"$BIN/simulate_field" --script kidnap --seed 4 --duration_s 20 --rate_hz 4 \
  --output "$TMP/field_kidnap.bag" --overwrite > /dev/null
for b in rosbag/field_bright.bag rosbag/field_dark.bag rosbag/field_switching.bag \
  "$TMP/field_kidnap.bag"; do
  n="$(basename "$b" .bag)"
  [ "$n" = field_switching ] || part "localization_global_$n" "$BIN/evaluate_localization" \
    --bag "$b" --particles 500 --output "$OUT/localization_global_$n"
  part "localization_track_$n" "$BIN/evaluate_localization" --bag "$b" --particles 500 \
    --init truth --output "$OUT/localization_track_$n"
done

# SLAM (papers/001 section 2): the monobot study, the simulator loop, the Intel lab's real log.
part monobot "$BIN/monobot_experiment" --runs 100 --output "$OUT/monobot"
python3 scripts/plot_monobot.py "$OUT/monobot" > /dev/null 2>&1 || true
part lines_office "$BIN/evaluate_lines" --bag rosbag/laser_office.bag --output "$OUT/lines_office"
part slam_loop "$BIN/evaluate_slam" --bag rosbag/laser_loop.bag --output "$OUT/slam_loop" \
  --name "simulator loop"
"$BIN/carmen_to_bag" --input data/laser/intel.clf.bz2 --output "$TMP/intel.bag" --overwrite \
  --max_issues 3 > /dev/null 2>&1
part slam_intel "$BIN/evaluate_slam" --bag "$TMP/intel.bag" \
  --output "$OUT/slam_intel" --name "Intel lab"
rm -f "$TMP/intel.bag"

# Histogram place recognition (papers/004): omni-directional camera, cloudy training and test runs,
# the paper's protocol (15 training and 15 test images per place).
"$BIN/simulate_indoor" --lighting cloudy --seed 11 --camera omni --camera_rate_hz 1 \
  --output "$TMP/places_train.bag" --overwrite > /dev/null 2>&1
"$BIN/train_places" --bag "$TMP/places_train.bag" --database "$TMP/places.sqlite" \
  --images_per_place 15 --mask auto > /dev/null 2>&1
"$BIN/simulate_indoor" --lighting cloudy --seed 12 --camera omni --camera_rate_hz 1 \
  --output "$TMP/places_test.bag" --overwrite > /dev/null 2>&1
part places "$BIN/evaluate_places" --database "$TMP/places.sqlite" --bag "$TMP/places_test.bag" \
  --images_per_place 15 --output "$OUT/places"
rm -f "$TMP"/places_*.bag

# Room classification (papers/002): SIFT on single images (Table 3) and the appearance MCL
# (Table 5), trained on a cloudy run and tested on another cloudy run.
"$BIN/simulate_indoor" --lighting cloudy --seed 11 --camera_rate_hz 2 --output "$TMP/rooms_train.bag" \
  --overwrite > /dev/null 2>&1
"$BIN/train_places" --bag "$TMP/rooms_train.bag" --database "$TMP/rooms.sqlite" --images_per_place 0 \
  --features --spaces hsv > /dev/null 2>&1
"$BIN/simulate_indoor" --lighting cloudy --seed 12 --camera_rate_hz 2 --output "$TMP/rooms_test.bag" \
  --overwrite > /dev/null 2>&1
for m in single mcl; do
  part "rooms_$m" "$BIN/evaluate_room_classification" --database "$TMP/rooms.sqlite" \
    --bag "$TMP/rooms_test.bag" --mode "$m" --output "$OUT/rooms_$m"
done
rm -f "$TMP"/rooms_*.bag

# Tracking (papers/001 section 3): the three synthetic experiments, seed 1, against CamShift.
for s in circles lambertian_rectangle distractor; do
  "$BIN/simulate_tracking" --scenario "$s" --seed 1 --output "$TMP/$s.bag" --overwrite > /dev/null
  part "tracking_$s" "$BIN/evaluate_tracking" --bag "$TMP/$s.bag" --mode condensation --peers camshift --output "$OUT/tracking_$s"
  rm -f "$TMP/$s.bag"
done

# Speed against the papers' (one core each).
part bench_rbpf "$BIN/bench_rbpf" --particles 100 --threads 1
part bench_tracker "$BIN/bench_tracker" --samples 100
part bench_lines "$BIN/bench_lines"
part bench_places "$BIN/bench_places" --images 10000 --space hsv
part bench_appearance "$BIN/bench_appearance"

python3 "$AP_ROOT/scripts/make_report.py" "$OUT" "$AP_ROOT/results/REPORT.md" "$SECONDS"
