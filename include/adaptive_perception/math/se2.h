#pragma once
// Rigid motions of the plane: a pose (x, y, yaw) of a child frame in a parent frame.
#include <Eigen/Core>

#include "adaptive_perception/math/angles.h"

namespace adaptive_perception::math {

struct SE2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;

  SE2() = default;
  SE2(double x, double y, double yaw) : x_m(x), y_m(y), yaw_rad(wrapAngle(yaw)) {}

  /// this * other: `other` expressed in this pose's frame, mapped to the parent frame.
  SE2 operator*(const SE2& other) const;
  /// The pose of the parent frame in this frame.
  SE2 inverse() const;
  /// Maps a point given in this pose's frame to the parent frame.
  Eigen::Vector2d transformPoint(const Eigen::Vector2d& p) const;
  /// 3x3 homogeneous matrix.
  Eigen::Matrix3d matrix() const;
};

/// The relative motion from `from` to `to`: from.inverse() * to (an odometry increment in from's
/// frame).
SE2 between(const SE2& from, const SE2& to);

/// The pose's point mirror through the parent frame's origin: (-x, -y, yaw + pi).
inline SE2 pointMirror(const SE2& p) { return SE2(-p.x_m, -p.y_m, p.yaw_rad + kPi); }

}  // namespace adaptive_perception::math
