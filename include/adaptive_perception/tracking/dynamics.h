#pragma once
// The CONDENSATION dynamics of papers/001 section 3.3, s_t = A s'_t + B w_t, with A a first-order
// (constant-velocity) model: written over the last two states as the second-order
// auto-regression
//   x_t = A1 x_{t-1} + A0 x_{t-2} + d + B w_t,   w_t ~ N(0, I),
// (constant velocity: A1 = 2I, A0 = -I, d = 0). learnAr2() estimates A1, A0, d and B from a
// training sequence of states by least squares (B B^T = covariance of the residuals, B its
// Cholesky factor), per dimension (`diagonal`, robust with short sequences) or with full matrices.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/tracking/color_distribution.h"

namespace adaptive_perception::tracking {

using StateMatrix = Eigen::Matrix<double, kStateDim, kStateDim>;

struct Ar2Model {
  StateMatrix a1 = 2.0 * StateMatrix::Identity();
  StateMatrix a0 = -StateMatrix::Identity();
  DistributionState d = DistributionState::Zero();
  StateMatrix b = StateMatrix::Zero();

  /// Constant velocity with independent noise of the given standard deviations.
  static Ar2Model constantVelocity(const DistributionState& noise_sd);
  /// The deterministic part A1 x1 + A0 x0 + d.
  DistributionState mean(const DistributionState& x1, const DistributionState& x0) const;
  /// A draw of x_t given x_{t-1} = x1 and x_{t-2} = x0.
  DistributionState sample(const DistributionState& x1, const DistributionState& x0,
                           math::Rng& rng) const;

  /// YAML (a1, a0: 8 x 8 row-major lists; d: 8; b: 8 x 8). Throws std::runtime_error naming the
  /// file and the bad key.
  static Ar2Model loadYaml(const std::string& path);
  void saveYaml(const std::string& path) const;  // written beside, then renamed
};

/// Least-squares estimate from a sequence of at least 4 x 19 states (full) or 20 (diagonal).
/// Throws std::invalid_argument when the sequence is too short.
Ar2Model learnAr2(const std::vector<DistributionState>& sequence, bool diagonal = true);

}  // namespace adaptive_perception::tracking
