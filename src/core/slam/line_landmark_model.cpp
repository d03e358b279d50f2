#include "adaptive_perception/slam/line_landmark_model.h"

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
  if (h_r) {
    *h_r << -sign * ca, -sign * sa, 0,  //
        0, 0, -1;
  }
  if (h_l) {
    *h_l << sign, sign * (p.x_m * sa - p.y_m * ca),  //
        0, 1;
  }
  return Line{rho, math::wrapAngle(alpha)};
}

Line lineToMap(const math::SE2& p, const Line& z, Eigen::Matrix<double, 2, 3>* g_r,
               Eigen::Matrix2d* g_z) {
  double alpha = z.alpha_rad + p.yaw_rad;
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  double rho = z.rho_m + p.x_m * ca + p.y_m * sa;
  // d(rho)/d(alpha) through alpha = z.alpha + theta:
  const double drho_dalpha = -p.x_m * sa + p.y_m * ca;
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
    *g_z << sign, sign * drho_dalpha,  //
        0, 1;
  }
  return Line{rho, math::wrapAngle(alpha)};
}

Eigen::Vector2d lineInnovation(const Line& z, const Line& h) {
  return Eigen::Vector2d(z.rho_m - h.rho_m, math::angleDiff(z.alpha_rad, h.alpha_rad));
}

}  // namespace adaptive_perception::slam
