#include "adaptive_perception/laser/line_fit.h"

#include <cmath>

namespace adaptive_perception::laser {

Eigen::Matrix2d polarPointCovariance(double r, double phi, double sr, double sphi) {
  Eigen::Matrix2d j;
  j << std::cos(phi), -r * std::sin(phi), std::sin(phi), r * std::cos(phi);
  return j * Eigen::Vector2d(sr * sr, sphi * sphi).asDiagonal() * j.transpose();
}

Eigen::Vector2d projectOnLine(const PolarLine& l, const Eigen::Vector2d& p) {
  const Eigen::Vector2d n(std::cos(l.alpha_rad), std::sin(l.alpha_rad));
  return p - lineDistance(l, p) * n;
}

PolarLine fitLine(const std::vector<Eigen::Vector2d>& pts, int first, int last,
                  const std::vector<Eigen::Matrix2d>& covs) {
  PolarLine out;
  const int n = last - first + 1;
  if (n < 2) return out;
  double mx = 0.0, my = 0.0;
  for (int i = first; i <= last; ++i) {
    mx += pts[i].x();
    my += pts[i].y();
  }
  mx /= n;
  my /= n;
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (int i = first; i <= last; ++i) {
    const double dx = pts[i].x() - mx, dy = pts[i].y() - my;
    sxx += dx * dx;
    syy += dy * dy;
    sxy += dx * dy;
  }
  // The normal direction minimising the sum of squared orthogonal distances.
  const double a = -2.0 * sxy, b = syy - sxx;
  double alpha = 0.5 * std::atan2(a, b);
  double rho = mx * std::cos(alpha) + my * std::sin(alpha);
  double sign = 1.0;
  if (rho < 0.0) {
    rho = -rho;
    alpha += 3.14159265358979323846;
    sign = -1.0;
  }
  alpha = std::remainder(alpha, 2.0 * 3.14159265358979323846);
  out.rho_m = rho;
  out.alpha_rad = alpha;
  if (covs.empty()) return out;
  // First-order propagation: d alpha = 1/2 (b dA - a dB) / (a^2 + b^2), with dA/dx_i = -2 (y_i -
  // my), dB/dx_i = -2 (x_i - mx), dA/dy_i = -2 (x_i - mx), dB/dy_i = 2 (y_i - my) (the mean's own
  // derivative terms sum to zero); rho = mx cos(alpha) + my sin(alpha) (before the sign flip).
  const double denom = a * a + b * b;
  const double alpha0 = 0.5 * std::atan2(a, b);
  const double c = std::cos(alpha0), s = std::sin(alpha0);
  const double drho_dalpha = -mx * s + my * c;
  for (int i = first; i <= last; ++i) {
    const double dx = pts[i].x() - mx, dy = pts[i].y() - my;
    Eigen::Matrix2d j;  // rows (rho, alpha), columns (x_i, y_i)
    const double dax = denom > 0 ? 0.5 * (b * (-2.0 * dy) - a * (-2.0 * dx)) / denom : 0.0;
    const double day = denom > 0 ? 0.5 * (b * (-2.0 * dx) - a * (2.0 * dy)) / denom : 0.0;
    j(1, 0) = dax;
    j(1, 1) = day;
    j(0, 0) = sign * (c / n + drho_dalpha * dax);
    j(0, 1) = sign * (s / n + drho_dalpha * day);
    out.cov += j * covs[i] * j.transpose();
  }
  return out;
}

}  // namespace adaptive_perception::laser
