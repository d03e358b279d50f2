#include "adaptive_perception/math/se2.h"

#include <cmath>

namespace adaptive_perception::math {

SE2 SE2::operator*(const SE2& o) const {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  return SE2(x_m + c * o.x_m - s * o.y_m, y_m + s * o.x_m + c * o.y_m, yaw_rad + o.yaw_rad);
}

SE2 SE2::inverse() const {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  return SE2(-c * x_m - s * y_m, s * x_m - c * y_m, -yaw_rad);
}

Eigen::Vector2d SE2::transformPoint(const Eigen::Vector2d& p) const {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  return {x_m + c * p.x() - s * p.y(), y_m + s * p.x() + c * p.y()};
}

Eigen::Matrix3d SE2::matrix() const {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  Eigen::Matrix3d m;
  m << c, -s, x_m, s, c, y_m, 0, 0, 1;
  return m;
}

SE2 between(const SE2& from, const SE2& to) { return from.inverse() * to; }

}  // namespace adaptive_perception::math
