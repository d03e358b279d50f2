#pragma once
// Sensor schedules of the simulators: the times (integer nanoseconds from the start, so that two
// sensors at commensurate rates meet exactly) of a sensor at `rate_hz` over [0, duration_s].
#include <cmath>
#include <cstdint>
#include <set>

namespace adaptive_perception::tools {

inline std::set<std::int64_t> tickTimesNs(double rate_hz, double duration_s) {
  std::set<std::int64_t> ticks;
  const auto end_ns = static_cast<std::int64_t>(duration_s * 1e9);
  for (std::int64_t k = 0;; ++k) {
    const auto t = static_cast<std::int64_t>(std::llround(k * 1e9 / rate_hz));
    if (t > end_ns) break;
    ticks.insert(t);
  }
  return ticks;
}

}  // namespace adaptive_perception::tools
