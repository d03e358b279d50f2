// bench_lines: line extraction throughput on one core for 181, 361 and 1081-beam scans of a
// simulated office (seeded), and the split step alone, recursive Douglas-Peucker against the hull
// tree, on a worst-case input (an alternating exponential zigzag: every split peels off one point,
// O(n^2) for the linear scan).
//
//   bench_lines --help   (every option with its default, unit and range)
//
// Last line: `bench_lines: scans_per_s_181=... scans_per_s_361=... scans_per_s_1081=...
//             split_ms_recursive_N=... split_ms_hull_tree_N=... (for N = 1000, 4000, 16000)`
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "adaptive_perception/laser/line_extraction.h"
#include "adaptive_perception/math/rng.h"
#include "bench_timing.h"
#include "command_line.h"

using namespace adaptive_perception;
using Clock = std::chrono::steady_clock;

namespace {
// Ranges inside a 10 x 6 m room with a pillar and a doorway, from a few poses, with noise.
laser::LaserScan2D officeScan(int beams, math::Rng& rng) {
  laser::LaserScan2D s;
  const double fov = beams == 181 ? M_PI : 1.5 * M_PI;
  s.angle_min_rad = -fov / 2;
  s.angle_increment_rad = fov / (beams - 1);
  s.range_min_m = 0.05;
  s.range_max_m = 30.0;
  const double ox = rng.uniform(-3, 3), oy = rng.uniform(-2, 2), yaw = rng.uniform(-M_PI, M_PI);
  const double walls[][4] = {{-5, -3, 5, -3},   {5, -3, 5, 3},    {5, 3, 1, 3},
                             {0, 3, -5, 3},     {-5, 3, -5, -3},  {1, -0.5, 2, -0.5},
                             {2, -0.5, 2, 0.5}, {2, 0.5, 1, 0.5}, {1, 0.5, 1, -0.5}};
  for (int i = 0; i < beams; ++i) {
    const double b = yaw + s.bearing(i);
    const Eigen::Vector2d d(std::cos(b), std::sin(b)), o(ox, oy);
    double best = s.range_max_m;
    for (const auto& w : walls) {
      const Eigen::Vector2d p(w[0], w[1]), e(w[2] - w[0], w[3] - w[1]);
      const double den = d.x() * e.y() - d.y() * e.x();
      if (std::fabs(den) < 1e-12) continue;
      const Eigen::Vector2d q = p - o;
      const double t = (q.x() * e.y() - q.y() * e.x()) / den,
                   u = (q.x() * d.y() - q.y() * d.x()) / den;
      if (t > 0 && u >= 0 && u <= 1) best = std::min(best, t);
    }
    s.ranges_m.push_back(
        static_cast<float>(best < s.range_max_m ? best + rng.gaussian(0, 0.01) : s.range_max_m));
  }
  return s;
}
}  // namespace

int main(int argc, char** argv) {
  tools::CommandLine cli("bench_lines",
                         "Line extraction throughput on one core for 181, 361 and 1081-beam scans, "
                         "and the split step alone on a worst-case input.");
  const double& seconds = cli.measurementSeconds(1.5);
  const std::uint64_t& seed = cli.seed();
  cli.parse(argc, argv);
  math::Rng rng(seed);
  std::string summary = "bench_lines:";
  for (int beams : {181, 361, 1081}) {
    std::vector<laser::LaserScan2D> scans;
    for (int k = 0; k < 50; ++k) scans.push_back(officeScan(beams, rng));
    laser::LineExtractor ex;
    long n = 0, segs = 0;
    const double scans_per_s = tools::unitsPerSecond(seconds, [&] {
      for (int k = 0; k < 100; ++k, ++n)
        segs += static_cast<long>(ex.extract(scans[n % scans.size()]).size());
      return 100;
    });
    std::printf("%5d beams: %.0f scans/s (%.1f segments per scan)\n", beams, scans_per_s,
                double(segs) / n);
    summary += " scans_per_s_" + std::to_string(beams) + "=" +
               std::to_string(static_cast<long>(scans_per_s));
  }
  // Worst case for the linear scan: p_k = (k, (-1)^k 1.02^k). The farthest point from the chord of
  // [0, j] is j - 1 (the largest swing to the other side), so every split peels off one point: n
  // levels of O(n) scans, O(n^2) in all, while the hull tree stays O(n log^2 n).
  for (int n : {1000, 4000, 16000}) {
    std::vector<Eigen::Vector2d> pts;
    for (int k = 0; k < n; ++k) pts.emplace_back(k, (k % 2 ? -1.0 : 1.0) * std::pow(1.02, k));
    for (auto method : {laser::SplitMethod::kRecursive, laser::SplitMethod::kHullTree}) {
      const auto t0 = Clock::now();
      const auto v = laser::simplifyPolyline(pts, 1e-12, method);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      const char* name = method == laser::SplitMethod::kRecursive ? "recursive" : "hull_tree";
      std::printf("split %-9s n=%5d: %8.2f ms (%zu vertices)\n", name, n, ms, v.size());
      char buf[96];
      std::snprintf(buf, sizeof buf, " split_ms_%s_%d=%.2f", name, n, ms);
      summary += buf;
    }
  }
  std::printf("%s\n", summary.c_str());
  return 0;
}
