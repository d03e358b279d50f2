#include "adaptive_perception/localization/pose_cluster.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <tuple>

#include "adaptive_perception/math/angles.h"

namespace adaptive_perception::localization {

std::vector<std::size_t> mainCluster(const std::vector<math::SE2>& poses,
                                     const std::vector<double>& weights) {
  // The cell of a coarse (x, y, yaw) grid with the most weight in it and its 26 neighbours (a
  // hypothesis spread over a few cells must outweigh a compact one that holds less weight), then
  // every particle near the weighted mean of that block.
  constexpr double kCell = 0.25, kRadius = 0.5, kYaw = 0.6;
  constexpr int kYawBins = 8;
  using Key = std::tuple<int, int, int>;
  std::map<Key, double> cells;
  auto key = [&](const math::SE2& p) {
    const int b =
        static_cast<int>(std::floor((p.yaw_rad + math::kPi) / (2.0 * math::kPi / kYawBins)));
    return std::make_tuple(static_cast<int>(std::floor(p.x_m / kCell)),
                           static_cast<int>(std::floor(p.y_m / kCell)),
                           ((b % kYawBins) + kYawBins) % kYawBins);
  };
  auto near = [&](const Key& a, const Key& b) {
    const int dyaw = std::abs(std::get<2>(a) - std::get<2>(b));
    return std::abs(std::get<0>(a) - std::get<0>(b)) <= 1 &&
           std::abs(std::get<1>(a) - std::get<1>(b)) <= 1 && std::min(dyaw, kYawBins - dyaw) <= 1;
  };
  for (std::size_t i = 0; i < poses.size(); ++i) cells[key(poses[i])] += weights[i];
  Key top{};
  double top_weight = -1.0;
  for (const auto& [k, w] : cells) {
    double block = 0.0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dyaw = -1; dyaw <= 1; ++dyaw) {
          const auto it =
              cells.find(std::make_tuple(std::get<0>(k) + dx, std::get<1>(k) + dy,
                                         (std::get<2>(k) + dyaw + kYawBins) % kYawBins));
          if (it != cells.end()) block += it->second;
        }
    if (block > top_weight) {
      top_weight = block;
      top = k;
    }
  }
  std::vector<std::size_t> in_block;
  for (std::size_t i = 0; i < poses.size(); ++i)
    if (near(key(poses[i]), top)) in_block.push_back(i);
  const math::SE2 c = weightedMean(poses, weights, in_block);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const math::SE2& p = poses[i];
    if (std::hypot(p.x_m - c.x_m, p.y_m - c.y_m) < kRadius &&
        std::fabs(math::angleDiff(p.yaw_rad, c.yaw_rad)) < kYaw)
      out.push_back(i);
  }
  return out;
}

math::SE2 weightedMean(const std::vector<math::SE2>& poses, const std::vector<double>& weights,
                       const std::vector<std::size_t>& idx) {
  double x = 0, y = 0, c = 0, s = 0, w = 0;
  for (std::size_t i : idx) {
    x += weights[i] * poses[i].x_m;
    y += weights[i] * poses[i].y_m;
    c += weights[i] * std::cos(poses[i].yaw_rad);
    s += weights[i] * std::sin(poses[i].yaw_rad);
    w += weights[i];
  }
  if (w <= 0.0) return math::SE2();
  return math::SE2(x / w, y / w, std::atan2(s, c));
}

Eigen::Matrix3d covarianceAbout(const std::vector<math::SE2>& poses,
                                const std::vector<double>& weights,
                                const std::vector<std::size_t>& idx, const math::SE2& m) {
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double w = 0.0;
  for (std::size_t i : idx) {
    const Eigen::Vector3d d(poses[i].x_m - m.x_m, poses[i].y_m - m.y_m,
                            math::angleDiff(poses[i].yaw_rad, m.yaw_rad));
    cov += weights[i] * d * d.transpose();
    w += weights[i];
  }
  return w > 0.0 ? Eigen::Matrix3d(cov / w) : cov;
}

PoseEstimate estimatePose(const std::vector<math::SE2>& poses, const std::vector<double>& weights) {
  std::vector<std::size_t> all(poses.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  PoseEstimate e;
  const std::vector<std::size_t> cluster = mainCluster(poses, weights);
  e.pose = weightedMean(poses, weights, cluster);
  e.covariance = covarianceAbout(poses, weights, cluster, e.pose);
  for (std::size_t i : cluster) e.cluster_weight += weights[i];
  e.spread_m = std::sqrt(covarianceAbout(poses, weights, all, weightedMean(poses, weights, all))
                             .topLeftCorner<2, 2>()
                             .trace());
  return e;
}

}  // namespace adaptive_perception::localization
