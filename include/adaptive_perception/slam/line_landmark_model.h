#pragma once
// Models of line-landmark EKF SLAM (Garulli et al. 2005, perception paper section 2.2, eqs. 1-9):
// the robot pose r = (x, y, theta) in map, line landmarks in Hessian normal form
//   x cos(alpha) + y sin(alpha) = rho,  rho >= 0, alpha in (-pi, pi],
// and their Jacobians. Every angle is wrapped; a line seen from the other side of its origin keeps
// rho >= 0 by flipping alpha by pi (the Jacobian of rho changes sign with it).
#include <Eigen/Core>

#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::slam {

struct Line {
  double rho_m = 0.0;
  double alpha_rad = 0.0;
};

/// Robot motion (eq. 5): pose composed with the odometry delta (dx, dy, dtheta) measured in the
/// previous robot frame. F_x = d(new pose)/d(pose), F_v = d(new pose)/d(delta).
math::SE2 predictPose(const math::SE2& pose, const math::SE2& delta, Eigen::Matrix3d* f_x,
                      Eigen::Matrix3d* f_v);

/// Observation: the map line as seen in the robot frame. H_r = dz/d(pose) (2x3), H_l = dz/d(line)
/// (2x2).
Line observeLine(const math::SE2& pose, const Line& map_line, Eigen::Matrix<double, 2, 3>* h_r,
                 Eigen::Matrix2d* h_l);

/// The Jacobians of observeLine evaluated at a chosen linearisation point: robot position (x, y)
/// and landmark direction alpha (the observation's Jacobians do not depend on the robot's heading
/// or the landmark's rho). `sign` is -1 when the observation is flipped to keep rho >= 0 (the
/// prediction decides it), else 1. First-estimates Jacobian filters call this with the first
/// estimates instead of the current ones.
void observeLineJacobians(double x_m, double y_m, double alpha_rad, double sign,
                          Eigen::Matrix<double, 2, 3>* h_r, Eigen::Matrix2d* h_l);

/// Inverse observation: the map line of a line observed in the robot frame. G_r = d(line)/d(pose),
/// G_z = d(line)/d(observation).
Line lineToMap(const math::SE2& pose, const Line& observed, Eigen::Matrix<double, 2, 3>* g_r,
               Eigen::Matrix2d* g_z);
/// lineToMap with its Jacobians linearised at the robot position (lin_x_m, lin_y_m) instead of the
/// pose's (the mean still uses `pose`).
Line lineToMap(const math::SE2& pose, const Line& observed, double lin_x_m, double lin_y_m,
               Eigen::Matrix<double, 2, 3>* g_r, Eigen::Matrix2d* g_z);

/// The line through two points (rho >= 0).
Line lineThrough(const Eigen::Vector2d& a, const Eigen::Vector2d& b);

/// The frame transform T that carries two non-parallel reference lines onto two others:
/// to[k] = lineToMap(T, from[k]) for k = 0, 1. Two undirected lines cannot tell a rotation th from
/// th + pi (about their intersection), so the rotation is the one nearer yaw_hint_rad. Used to
/// express ground truth in the frame an anchored map defines. Returns false when the lines are
/// (nearly) parallel.
bool transformBetweenLinePairs(const Line from[2], const Line to[2], math::SE2* t,
                               double yaw_hint_rad = 0.0);

/// The innovation z - h with the angle wrapped.
Eigen::Vector2d lineInnovation(const Line& z, const Line& predicted);

}  // namespace adaptive_perception::slam
