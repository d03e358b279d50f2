#!/usr/bin/env bash
# Fuzzes every parser of user files (test/fuzz/fuzz_*.cpp: CARMEN logs, relations files, field and
# world YAML, colour priors, tracking dynamics, image-list CSVs, place databases, saved line maps,
# map_server YAML) with libFuzzer +
# AddressSanitizer + UndefinedBehaviorSanitizer (clang), each for a bounded time, starting from its
# seed corpus in test/fuzz/corpus/<parser> (the target's name without fuzz_). The corpus grown by a run is kept in
# results/fuzz/<target>/corpus; a crashing input is written to results/fuzz/<target>/ (crash-*,
# leak-*, timeout-*): copy it to test/fuzz/regressions/<parser>/ once fixed, and
# scripts/check_core.sh replays it from then on. Prints per target
#   fuzz: target=T seconds=S runs=N corpus=C crashes=K
# and exits non-zero when any target crashed. Build in .ws/fuzz (git-ignored).
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET=60] [TARGET ...]
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
SECONDS_PER_TARGET="${1:-60}"
shift || true
BUILD="$AP_WS/fuzz"
OUT="$AP_ROOT/results/fuzz"
JOBS="${AP_JOBS:-$(nproc)}"
command -v clang++ > /dev/null || { echo "fuzz: clang++ missing (scripts/setup.sh installs it)"; exit 1; }
mkdir -p "$BUILD" "$OUT"
if ! { CXX=clang++ cmake -S "$AP_ROOT/test/standalone" -B "$BUILD" -DCMAKE_BUILD_TYPE=None \
         -DAP_SANITIZE=ON -DAP_FUZZ=ON && cmake --build "$BUILD" -j"$JOBS"; } > "$BUILD/build.log" 2>&1; then
  tail -n 40 "$BUILD/build.log"; echo "fuzz: build FAILED (log: $BUILD/build.log)"; exit 1
fi
targets=("$@")
if [ "${#targets[@]}" -eq 0 ]; then
  for f in "$AP_ROOT"/test/fuzz/fuzz_*.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi
export ASAN_OPTIONS="detect_leaks=1"
status=0
for t in "${targets[@]}"; do
  dir="$OUT/$t"
  mkdir -p "$dir/corpus"
  # Seeds and earlier crashes join the kept corpus; -max_total_time bounds the run.
  dirs=("$dir/corpus")
  for d in "$AP_ROOT/test/fuzz/corpus/${t#fuzz_}" "$AP_ROOT/test/fuzz/regressions/${t#fuzz_}"; do
    [ -d "$d" ] && dirs+=("$d")
  done
  touch "$dir/.run_start"  # artifacts of earlier runs stay, but are not counted again
  "$BUILD/$t" "${dirs[@]}" -max_total_time="$SECONDS_PER_TARGET" -timeout=10 -rss_limit_mb=2048 -max_len=16384 \
    -artifact_prefix="$dir/" -print_final_stats=1 > "$dir/log.txt" 2>&1
  rc=$?
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log.txt" | tail -n 1)"
  crashes="$(find "$dir" -maxdepth 1 -newer "$dir/.run_start" \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)"
  echo "fuzz: target=$t seconds=$SECONDS_PER_TARGET runs=${runs:-0} corpus=$(ls "$dir/corpus" | wc -l) crashes=$crashes"
  if [ "$rc" -ne 0 ] || [ "$crashes" -gt 0 ]; then
    status=1
    grep -m 3 -E 'ERROR: (AddressSanitizer|libFuzzer|LeakSanitizer)|runtime error' "$dir/log.txt" | sed 's/^/  /'
  fi
done
exit $status
