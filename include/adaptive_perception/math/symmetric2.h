#pragma once
// Symmetric 2x2 matrices in closed form: a line landmark's covariance (rho, alpha), the translation
// block of an information matrix. Eigen's iterative solver does the same work at many times the
// compile cost, in every file that used it.
#include <Eigen/Core>
#include <cmath>

namespace adaptive_perception::math {

/// Eigenvalues of a symmetric 2x2 matrix (its lower triangle is read), ascending: the larger is
/// (a + d) / 2 + hypot((a - d) / 2, b), the smaller det / larger (no cancellation when both are
/// positive), or (a + d) / 2 - hypot(...) when the larger is not positive.
inline Eigen::Vector2d symmetricEigenvalues(const Eigen::Matrix2d& m) {
  const double a = m(0, 0), b = m(1, 0), d = m(1, 1);
  const double mean = 0.5 * (a + d), r = std::hypot(0.5 * (a - d), b);
  const double larger = mean + r;
  const double smaller = larger > 0.0 ? (a * d - b * b) / larger : mean - r;
  return {smaller, larger};
}

/// True when `c` can be a covariance: finite, symmetric to 1e-9 of (1 + its largest entry), and
/// positive semi-definite (smallest eigenvalue >= -1e-12). The map readers' test of a landmark.
inline bool isCovariance(const Eigen::Matrix2d& c) {
  return c.allFinite() && std::fabs(c(0, 1) - c(1, 0)) <= 1e-9 * (1.0 + c.cwiseAbs().maxCoeff()) &&
         symmetricEigenvalues(c)[0] >= -1e-12;
}

}  // namespace adaptive_perception::math
