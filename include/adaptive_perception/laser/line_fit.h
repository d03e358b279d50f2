#pragma once
// Total-least-squares line fit in Hessian normal form, x cos(alpha) + y sin(alpha) = rho (rho >=
// 0), with the 2x2 covariance of (rho, alpha) propagated to first order from each point's
// covariance (from range and bearing noise) through the closed-form derivatives of the fit.
#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace adaptive_perception::laser {

struct PolarLine {
  double rho_m = 0.0;
  double alpha_rad = 0.0;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();  // of (rho, alpha)
};

/// Fits points[first..last] (inclusive). `point_covs` may be empty (then cov is zero) or one 2x2
/// per point.
PolarLine fitLine(const std::vector<Eigen::Vector2d>& points, int first, int last,
                  const std::vector<Eigen::Matrix2d>& point_covs);

/// Cartesian covariance of a return at (range, bearing) with the given range and bearing noise.
Eigen::Matrix2d polarPointCovariance(double range_m, double bearing_rad, double range_std_m,
                                     double bearing_std_rad);

/// Signed distance of p from the line.
inline double lineDistance(const PolarLine& l, const Eigen::Vector2d& p) {
  return p.x() * std::cos(l.alpha_rad) + p.y() * std::sin(l.alpha_rad) - l.rho_m;
}
/// Orthogonal projection of p onto the line.
Eigen::Vector2d projectOnLine(const PolarLine& l, const Eigen::Vector2d& p);

}  // namespace adaptive_perception::laser
