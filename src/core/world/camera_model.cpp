#include "adaptive_perception/world/camera_model.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace adaptive_perception::world {

PinholeCamera PinholeCamera::fromFieldOfView(int w, int h, double hfov, double vfov) {
  PinholeCamera c;
  c.width_px = w;
  c.height_px = h;
  c.fx_px = 0.5 * w / std::tan(0.5 * hfov);
  c.fy_px = 0.5 * h / std::tan(0.5 * vfov);
  c.cx_px = 0.5 * w;
  c.cy_px = 0.5 * h;
  c.validate();
  return c;
}

PinholeCamera PinholeCamera::aiboErs7() {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  return fromFieldOfView(208, 160, 56.9 * kDeg, 45.2 * kDeg);
}

bool PinholeCamera::project(const Eigen::Vector3d& p, Eigen::Vector2d* uv) const {
  if (p.z() <= 1e-9) return false;
  *uv = {fx_px * p.x() / p.z() + cx_px, fy_px * p.y() / p.z() + cy_px};
  return true;
}

void PinholeCamera::validate() const {
  if (width_px <= 0 || height_px <= 0 || width_px > 65535 || height_px > 65535)
    throw std::invalid_argument("camera size " + std::to_string(width_px) + "x" +
                                std::to_string(height_px) + " must be within 1..65535 pixels");
  if (!(fx_px > 0.0) || !(fy_px > 0.0))
    throw std::invalid_argument("camera focal lengths must be positive");
}

Eigen::Isometry3d HeadChain::basePan(double pan, double lean) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(base_to_pan_m)
      .rotate(Eigen::AngleAxisd(lean, Eigen::Vector3d::UnitY()))
      .rotate(Eigen::AngleAxisd(pan, Eigen::Vector3d::UnitZ()));
  return t;
}

Eigen::Isometry3d HeadChain::panTilt(double tilt) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(pan_to_tilt_m).rotate(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitY()));
  return t;
}

Eigen::Isometry3d HeadChain::tiltCamera() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(tilt_to_camera_m)
      .rotate(Eigen::AngleAxisd(camera_pitch_rad, Eigen::Vector3d::UnitY()));
  return t;
}

Eigen::Isometry3d HeadChain::cameraOptical() {
  // Columns: optical x (right) = -y_link, optical y (down) = -z_link, optical z (forward) = x_link.
  Eigen::Matrix3d r;
  r << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = r;
  return t;
}

Eigen::Isometry3d HeadChain::baseToOptical(double pan, double tilt, double lean) const {
  return basePan(pan, lean) * panTilt(tilt) * tiltCamera() * cameraOptical();
}

double pitchBelowHorizontal(const Eigen::Quaterniond& orientation) {
  const Eigen::Vector3d x = orientation.normalized() * Eigen::Vector3d::UnitX();
  return std::atan2(-x.z(), std::hypot(x.x(), x.y()));
}

Eigen::Isometry3d planarToIsometry(const math::SE2& pose, double z, double roll, double pitch) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(Eigen::Vector3d(pose.x_m, pose.y_m, z));
  t.rotate(Eigen::AngleAxisd(pose.yaw_rad, Eigen::Vector3d::UnitZ()) *
           Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
           Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()));
  return t;
}

math::SE2 isometryToPlanar(const Eigen::Isometry3d& t) {
  const Eigen::Vector3d x = t.linear().col(0);
  return math::SE2(t.translation().x(), t.translation().y(), std::atan2(x.y(), x.x()));
}

}  // namespace adaptive_perception::world
