// LineEkfSlam's landmark extents (line_ekf_slam.h): the pieces of wall seen along each landmark
// line, for drawing and for merging. They are not part of the filter's state; the filter's model
// and updates are in line_ekf_slam.cpp, its data association in data_association.cpp.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "adaptive_perception/slam/line_ekf_slam.h"

namespace adaptive_perception::slam {

void LineEkfSlam::extendExtent(int i, const LineObservation& obs) {
  if (i >= numLandmarks()) {
    FixedLandmark& f = fixed_[i - numLandmarks()];
    extendExtent(f.line, obs, &f.info);
  } else {
    extendExtent(landmark(i), obs, &landmarks_[i]);
  }
}

void LineEkfSlam::extendExtent(const Line& l, const LineObservation& obs, Landmark* lm_out) {
  // Endpoints to map, projected on the landmark line, merged with the extent along its direction.
  const math::SE2 r = pose();
  const double c = std::cos(r.yaw_rad), s = std::sin(r.yaw_rad);
  auto to_map = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(r.x_m + c * p.x() - s * p.y(), r.y_m + s * p.x() + c * p.y());
  };
  const Eigen::Vector2d n(std::cos(l.alpha_rad), std::sin(l.alpha_rad)), t(-n.y(), n.x());
  const Eigen::Vector2d foot = l.rho_m * n;
  Landmark& lm = *lm_out;
  // Intervals along the line: the known pieces and the new segment, sorted and joined.
  std::vector<std::pair<double, double>> iv;
  auto interval = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const double ua = t.dot(a - foot), ub = t.dot(b - foot);
    iv.emplace_back(std::min(ua, ub), std::max(ua, ub));
  };
  interval(to_map(obs.start_m), to_map(obs.end_m));
  for (const auto& pc : lm.pieces) interval(pc.first, pc.second);
  std::sort(iv.begin(), iv.end());
  std::vector<std::pair<double, double>> joined;
  for (const auto& x : iv) {
    if (!joined.empty() && x.first <= joined.back().second + Landmark::kPieceGapM)
      joined.back().second = std::max(joined.back().second, x.second);
    else
      joined.push_back(x);
  }
  lm.pieces.clear();
  for (const auto& x : joined) lm.pieces.emplace_back(foot + x.first * t, foot + x.second * t);
  lm.start_m = lm.pieces.front().first;
  lm.end_m = lm.pieces.back().second;
}

}  // namespace adaptive_perception::slam
