#pragma once
// The colour distribution tracked by CONDENSATION (papers/001 section 3.3): the set C_t of the
// target's pixel colours (points of the unit cube, color_histogram.h), parameterised by
//   x = [m (centroid, 3), lambda (principal-component magnitudes, 3), theta, phi]
// where lambda are the standard deviations along the principal axes (largest first) and theta,
// phi the angles that turn the principal axes of C_{t-1} into those of C_t: in the principal
// frame of C_{t-1}, the rotation R(theta, phi) = Rz(theta) Ry(-phi) moves the first axis by theta
// towards the second and by phi towards the third.
//
// warpDistribution() applies a state to a reference distribution: every point p of C_ref goes to
//   m + E_ref R(theta, phi) diag(lambda / lambda_ref) E_ref^T (p - m_ref),
// so the warped set has exactly the state's centroid and principal magnitudes, its axes are the
// reference's turned by (theta, phi), and it keeps the reference's point count.
#include <Eigen/Core>
#include <vector>

namespace adaptive_perception::tracking {

using ColorPoints = std::vector<Eigen::Vector3f>;
using DistributionState = Eigen::Matrix<double, 8, 1>;  // m (3), lambda (3), theta, phi
constexpr int kStateDim = 8;

struct ColorStats {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d magnitudes = Eigen::Vector3d::Zero();  // sd along each axis, descending
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();    // columns: principal axes, det +1
};

/// Mean and principal components of a point set; throws std::invalid_argument when it is empty.
ColorStats colorStats(const ColorPoints& points);

/// The rotation, in world (colour-space) coordinates, that a state's angles apply to `axes`.
Eigen::Matrix3d alignmentRotation(const Eigen::Matrix3d& axes, double theta, double phi);

/// The angles (theta, phi) that best turn the first axis of `from` onto that of `to` (axes'
/// signs made to agree first, as principal axes have no sign).
Eigen::Vector2d alignmentAngles(const Eigen::Matrix3d& from, const Eigen::Matrix3d& to);

/// The state [mean, magnitudes, 0, 0] of a distribution (no turn from itself).
DistributionState stateOf(const ColorStats& stats);

/// The warp described above. Magnitudes below `min_magnitude` (in the state or the reference) are
/// raised to it, so a flat (single-colour) reference never divides by zero.
ColorPoints warpDistribution(const ColorPoints& reference, const ColorStats& reference_stats,
                             const DistributionState& state, double min_magnitude = 1e-3);

}  // namespace adaptive_perception::tracking
