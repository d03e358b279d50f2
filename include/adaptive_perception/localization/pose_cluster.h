#pragma once
// The pose estimate of a weighted particle set that may hold several hypotheses: the weighted mean
// of the main cluster, not of all particles, whose mean may lie between two hypotheses.
//
// The main cluster: the cell of a coarse grid (0.25 m x 0.25 m x 45 degrees) whose 3x3x3 block of
// cells holds the most weight (a hypothesis spread over a few cells must outweigh a compact one
// that holds less weight), then every particle within 0.5 m and 0.6 rad of that block's weighted
// mean. Means are circular in yaw; covariances are taken about the given mean with the yaw
// difference wrapped. Weights need not be normalised; an empty or weightless set gives the origin
// and a zero covariance.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::localization {

struct PoseEstimate {
  math::SE2 pose;               // weighted mean (circular in yaw) of the main cluster
  Eigen::Matrix3d covariance;   // of the main cluster (x, y, yaw)
  double cluster_weight = 0.0;  // share of the weight in the main cluster
  double spread_m = 0.0;        // sqrt(trace of the x-y covariance) of ALL particles
};

/// The indices of the main cluster (see above).
std::vector<std::size_t> mainCluster(const std::vector<math::SE2>& poses,
                                     const std::vector<double>& weights);
/// The weighted mean of poses[idx] (circular in yaw).
math::SE2 weightedMean(const std::vector<math::SE2>& poses, const std::vector<double>& weights,
                       const std::vector<std::size_t>& idx);
/// The weighted covariance (x, y, yaw) of poses[idx] about `mean`.
Eigen::Matrix3d covarianceAbout(const std::vector<math::SE2>& poses,
                                const std::vector<double>& weights,
                                const std::vector<std::size_t>& idx, const math::SE2& mean);
/// The estimate: the main cluster's mean, covariance and weight, and the spread of all poses.
PoseEstimate estimatePose(const std::vector<math::SE2>& poses, const std::vector<double>& weights);

}  // namespace adaptive_perception::localization
