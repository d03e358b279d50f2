#include "adaptive_perception/slam/line_landmark_model.h"

#include <Eigen/LU>
#include <cmath>

#include "adaptive_perception/math/angles.h"

namespace adaptive_perception::slam {

math::SE2 predictPose(const math::SE2& p, const math::SE2& d, Eigen::Matrix3d* f_x,
                      Eigen::Matrix3d* f_v) {
  const double c = std::cos(p.yaw_rad), s = std::sin(p.yaw_rad);
  if (f_x) {
    *f_x << 1, 0, -d.x_m * s - d.y_m * c,  //
        0, 1, d.x_m * c - d.y_m * s,       //
        0, 0, 1;
  }
  if (f_v) {
    *f_v << c, -s, 0,  //
        s, c, 0,       //
        0, 0, 1;
  }
  return math::SE2(p.x_m + d.x_m * c - d.y_m * s, p.y_m + d.x_m * s + d.y_m * c,
                   math::wrapAngle(p.yaw_rad + d.yaw_rad));
}

void observeLineJacobians(double x, double y, double alpha, double sign,
                          Eigen::Matrix<double, 2, 3>* h_r, Eigen::Matrix2d* h_l) {
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  if (h_r) {
    *h_r << -sign * ca, -sign * sa, 0,  //
        0, 0, -1;
  }
  if (h_l) {
    *h_l << sign, sign * (x * sa - y * ca),  //
        0, 1;
  }
}

Line observeLine(const math::SE2& p, const Line& l, Eigen::Matrix<double, 2, 3>* h_r,
                 Eigen::Matrix2d* h_l) {
  const double ca = std::cos(l.alpha_rad), sa = std::sin(l.alpha_rad);
  double rho = l.rho_m - (p.x_m * ca + p.y_m * sa);
  double alpha = l.alpha_rad - p.yaw_rad;
  double sign = 1.0;
  if (rho < 0.0) {  // the robot is beyond the line from the map origin: flip to keep rho >= 0
    rho = -rho;
    alpha += math::kPi;
    sign = -1.0;
  }
  observeLineJacobians(p.x_m, p.y_m, l.alpha_rad, sign, h_r, h_l);
  return Line{rho, math::wrapAngle(alpha)};
}

Line lineToMap(const math::SE2& p, const Line& z, Eigen::Matrix<double, 2, 3>* g_r,
               Eigen::Matrix2d* g_z) {
  return lineToMap(p, z, p.x_m, p.y_m, g_r, g_z);
}

Line lineToMap(const math::SE2& p, const Line& z, double lin_x, double lin_y,
               Eigen::Matrix<double, 2, 3>* g_r, Eigen::Matrix2d* g_z) {
  double alpha = z.alpha_rad + p.yaw_rad;
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  double rho = z.rho_m + p.x_m * ca + p.y_m * sa;
  // d(rho)/d(alpha) through alpha = z.alpha + theta, at the linearisation point (G_r) and at the
  // pose (G_z, which only carries the observation noise):
  const double drho_dalpha = -lin_x * sa + lin_y * ca;
  const double drho_dalpha_z = -p.x_m * sa + p.y_m * ca;
  double sign = 1.0;
  if (rho < 0.0) {
    rho = -rho;
    alpha += math::kPi;
    sign = -1.0;
  }
  if (g_r) {
    *g_r << sign * ca, sign * sa, sign * drho_dalpha,  //
        0, 0, 1;
  }
  if (g_z) {
    *g_z << sign, sign * drho_dalpha_z,  //
        0, 1;
  }
  return Line{rho, math::wrapAngle(alpha)};
}

Eigen::Vector2d lineInnovation(const Line& z, const Line& h) {
  return Eigen::Vector2d(z.rho_m - h.rho_m, math::angleDiff(z.alpha_rad, h.alpha_rad));
}

Line lineThrough(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = (b - a).normalized();
  Line l{a.x() * d.y() - a.y() * d.x(), std::atan2(-d.x(), d.y())};  // normal (d.y, -d.x)
  if (l.rho_m < 0.0) {
    l.rho_m = -l.rho_m;
    l.alpha_rad = math::wrapAngle(l.alpha_rad + math::kPi);
  }
  return l;
}

bool transformBetweenLinePairs(const Line from[2], const Line to[2], math::SE2* t,
                               double yaw_hint_rad) {
  // Rotation: the normals turn by th or th + pi (a representation may flip to keep rho >= 0).
  double th = math::wrapAngle(to[0].alpha_rad - from[0].alpha_rad);
  if (std::cos(th - yaw_hint_rad) < 0.0) th = math::wrapAngle(th + math::kPi);
  Eigen::Matrix2d a;
  Eigen::Vector2d b;
  for (int k = 0; k < 2; ++k) {
    // The signed normal of from[k] after rotation, aligned with to[k]'s normal.
    double sign = 1.0;
    double rot_alpha = from[k].alpha_rad + th;
    if (std::cos(math::wrapAngle(rot_alpha - to[k].alpha_rad)) < 0.0) {
      sign = -1.0;
      rot_alpha += math::kPi;
    }
    // Line n.x = sign rho in the new frame after translation t: n.(x - t) ... so
    // to.rho = sign from.rho + n . t with n the normal of to[k].
    const Eigen::Vector2d n(std::cos(rot_alpha), std::sin(rot_alpha));
    a.row(k) = n.transpose();
    b[k] = to[k].rho_m - sign * from[k].rho_m;
  }
  if (std::fabs(a.determinant()) < 1e-3) return false;
  const Eigen::Vector2d tr = a.inverse() * b;
  *t = math::SE2(tr.x(), tr.y(), th);
  return true;
}

}  // namespace adaptive_perception::slam
