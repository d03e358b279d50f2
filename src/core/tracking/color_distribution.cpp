#include "adaptive_perception/tracking/color_distribution.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace adaptive_perception::tracking {

ColorStats colorStats(const ColorPoints& points) {
  if (points.empty()) throw std::invalid_argument("colorStats: empty colour distribution");
  ColorStats s;
  for (const auto& p : points) s.mean += p.cast<double>();
  s.mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector3d d = p.cast<double>() - s.mean;
    cov += d * d.transpose();
  }
  cov /= static_cast<double>(points.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  // Eigen sorts ascending; principal axes come largest first.
  for (int k = 0; k < 3; ++k) {
    s.magnitudes[k] = std::sqrt(std::max(0.0, eig.eigenvalues()[2 - k]));
    s.axes.col(k) = eig.eigenvectors().col(2 - k);
  }
  if (s.axes.determinant() < 0) s.axes.col(2) = -s.axes.col(2);
  return s;
}

Eigen::Matrix3d alignmentRotation(const Eigen::Matrix3d& axes, double theta, double phi) {
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(-phi, Eigen::Vector3d::UnitY()))
                                .toRotationMatrix();
  return axes * r * axes.transpose();
}

Eigen::Vector2d alignmentAngles(const Eigen::Matrix3d& from, const Eigen::Matrix3d& to) {
  Eigen::Vector3d first = from.transpose() * to.col(0);  // `to`'s first axis in `from`'s frame
  if (first[0] < 0) first = -first;
  first.normalize();
  // Rz(theta) Ry(-phi) e1 = (cos theta cos phi, sin theta cos phi, sin phi).
  const double phi = std::asin(std::clamp(first[2], -1.0, 1.0));
  const double theta = std::atan2(first[1], first[0]);
  return {theta, phi};
}

DistributionState stateOf(const ColorStats& stats) {
  DistributionState x;
  x << stats.mean, stats.magnitudes, 0.0, 0.0;
  return x;
}

ColorPoints warpDistribution(const ColorPoints& reference, const ColorStats& ref,
                             const DistributionState& state, double min_magnitude) {
  const Eigen::Vector3d m = state.head<3>();
  Eigen::Vector3d scale;
  for (int k = 0; k < 3; ++k)
    scale[k] = std::max(min_magnitude, state[3 + k]) / std::max(min_magnitude, ref.magnitudes[k]);
  const Eigen::Matrix3d warp = alignmentRotation(ref.axes, state[6], state[7]) * ref.axes *
                               scale.asDiagonal() * ref.axes.transpose();
  const Eigen::Matrix3f wf = warp.cast<float>();
  const Eigen::Vector3f mf = m.cast<float>(), m0 = ref.mean.cast<float>();
  ColorPoints out;
  out.reserve(reference.size());
  for (const auto& p : reference) out.push_back(mf + wf * (p - m0));
  return out;
}

}  // namespace adaptive_perception::tracking
