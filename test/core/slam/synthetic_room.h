#pragma once
// A synthetic room for the scan-matching tests (scan_matcher_test, pose_graph_test): its walls as
// segments, and a noise-free or noisy 180-degree laser scan ray-cast from a pose.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::test {

// Walls of a 10 x 6 m room with a pillar and a side wall, as segments.
struct Segment {
  Eigen::Vector2d a, b;
};
inline std::vector<Segment> room() {
  return {{{0, 0}, {10, 0}}, {{10, 0}, {10, 6}}, {{10, 6}, {0, 6}}, {{0, 6}, {0, 0}},
          {{4, 2}, {5, 2}},  {{5, 2}, {5, 3}},   {{5, 3}, {4, 3}},  {{4, 3}, {4, 2}},
          {{7, 6}, {7, 4}}};
}

/// The walls of room() sampled every 2 cm: a map for a likelihood field.
inline std::vector<Eigen::Vector2d> roomPoints() {
  std::vector<Eigen::Vector2d> pts;
  for (const auto& s : room()) {
    const int n = static_cast<int>((s.b - s.a).norm() / 0.02);
    for (int k = 0; k <= n; ++k) pts.push_back(s.a + (s.b - s.a) * k / std::max(1, n));
  }
  return pts;
}

/// A round hall: a regular `sides`-gon of circumradius `radius_m` about the origin. With
/// `doorway_m` > 0 the edges within doorway_m / 2 of the +x axis (on the +x side) are left out
/// and a 2 m corridor leads off through the gap.
inline std::vector<Segment> roundHall(double radius_m, int sides, double doorway_m = 0.0) {
  std::vector<Segment> walls;
  double gap_lo = 0.0, gap_hi = 0.0;  // the y of the gap's jambs
  for (int i = 0; i < sides; ++i) {
    const double a0 = 2 * M_PI * i / sides, a1 = 2 * M_PI * (i + 1) / sides;
    const Segment s{{radius_m * std::cos(a0), radius_m * std::sin(a0)},
                    {radius_m * std::cos(a1), radius_m * std::sin(a1)}};
    const Eigen::Vector2d mid = 0.5 * (s.a + s.b);
    if (doorway_m > 0 && mid.x() > 0 && std::fabs(mid.y()) < 0.5 * doorway_m) {
      gap_lo = std::min({gap_lo, s.a.y(), s.b.y()});
      gap_hi = std::max({gap_hi, s.a.y(), s.b.y()});
      continue;
    }
    walls.push_back(s);
  }
  if (doorway_m > 0) {
    const double x = std::sqrt(radius_m * radius_m - gap_hi * gap_hi);
    walls.push_back({{x, gap_lo}, {x + 2.0, gap_lo}});
    walls.push_back({{x, gap_hi}, {x + 2.0, gap_hi}});
  }
  return walls;
}

/// Ray-casts `beams` beams (181 unless given) over 180 degrees from `pose` against `walls`: the
/// hit points (robot frame) closer than max_range_m.
inline std::vector<Eigen::Vector2d> scanOf(const std::vector<Segment>& walls, const math::SE2& pose,
                                           std::mt19937* rng, double noise_m, double max_range_m,
                                           int beams = 181);

/// Ray-casts 181 beams over 180 degrees from `pose` in room(): the hit points in the robot frame.
inline std::vector<Eigen::Vector2d> scanFrom(const math::SE2& pose, std::mt19937* rng = nullptr,
                                             double noise_m = 0.0) {
  return scanOf(room(), pose, rng, noise_m, 20.0);
}

inline std::vector<Eigen::Vector2d> scanOf(const std::vector<Segment>& walls, const math::SE2& pose,
                                           std::mt19937* rng, double noise_m, double max_range_m,
                                           int beams) {
  std::vector<Eigen::Vector2d> out;
  std::normal_distribution<double> n(0.0, noise_m > 0 ? noise_m : 1.0);
  for (int i = 0; i < beams; ++i) {
    const double b = -M_PI / 2 + i * M_PI / (beams - 1);
    const Eigen::Vector2d o(pose.x_m, pose.y_m);
    const Eigen::Vector2d d(std::cos(pose.yaw_rad + b), std::sin(pose.yaw_rad + b));
    double best = 1e9;
    for (const auto& s : walls) {
      const Eigen::Vector2d e = s.b - s.a;
      const double den = d.x() * (-e.y()) - d.y() * (-e.x());
      if (std::fabs(den) < 1e-12) continue;
      const Eigen::Vector2d r = s.a - o;
      const double t = (r.x() * (-e.y()) - r.y() * (-e.x())) / den;
      const double u = (d.x() * r.y() - d.y() * r.x()) / den;
      if (t > 0.05 && u >= 0 && u <= 1) best = std::min(best, t);
    }
    if (best > max_range_m) continue;
    if (rng && noise_m > 0) best += n(*rng);
    out.emplace_back(best * std::cos(b), best * std::sin(b));
  }
  return out;
}

}  // namespace adaptive_perception::test
