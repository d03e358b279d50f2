#pragma once
// The benchmarks' timed loop: a piece of work repeated until a wall-clock budget is spent, so
// that a measurement lasts long enough to be steady on any machine, and the rate it ran at.
#include <chrono>

namespace adaptive_perception::tools {

/// Calls `batch` until `seconds` of wall-clock time have passed (at least once); `batch` returns
/// how many units of work (frames, scans, calls) it did. Returns the units per second.
template <class Batch>
double unitsPerSecond(double seconds, Batch&& batch) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  long units = 0;
  double elapsed_s = 0.0;
  do {
    units += batch();
    elapsed_s = std::chrono::duration<double>(Clock::now() - t0).count();
  } while (elapsed_s < seconds);
  return units / elapsed_s;
}

}  // namespace adaptive_perception::tools
