#pragma once
// Pinhole camera (no distortion) and the AIBO head chain that places it on the robot.
//
// Frames (REP-103/105): base_link on the body, x forward, z up, at ground level under the body
// centre; head_pan_link rotates about z (pan, positive = left); head_tilt_link rotates about y
// (tilt, positive = nose down); camera_link is the lens, x forward; camera_optical_frame is z
// forward, x right, y down.
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::world {

struct PinholeCamera {
  int width_px = 208;  // AIBO ERS-7 camera, high-resolution layer
  int height_px = 160;
  double fx_px = 0.0, fy_px = 0.0, cx_px = 0.0, cy_px = 0.0;

  /// A camera of the given size whose image spans the given full fields of view (ERS-7: 56.9 x 45.2
  /// deg).
  static PinholeCamera fromFieldOfView(int width_px, int height_px, double hfov_rad,
                                       double vfov_rad);
  /// The ERS-7-like default: 208 x 160, 56.9 x 45.2 degrees.
  static PinholeCamera aiboErs7();

  /// Unit-free ray through pixel centre (u + 0.5, v + 0.5) in the optical frame, z = 1.
  Eigen::Vector3d rayThrough(double u_px, double v_px) const {
    return {(u_px + 0.5 - cx_px) / fx_px, (v_px + 0.5 - cy_px) / fy_px, 1.0};
  }
  /// Projects a point in the optical frame; false when behind the camera.
  bool project(const Eigen::Vector3d& p_optical, Eigen::Vector2d* uv_px) const;
  /// Throws std::invalid_argument on a non-positive size or focal length.
  void validate() const;
};

/// Geometry of the head chain; translations in metres in the parent frame.
struct HeadChain {
  Eigen::Vector3d base_to_pan_m{0.07, 0.0, 0.19};  // neck joint above the shoulders
  Eigen::Vector3d pan_to_tilt_m{0.0, 0.0, 0.04};
  Eigen::Vector3d tilt_to_camera_m{0.075, 0.0, 0.02};  // snout camera ahead of the tilt axis
  double camera_pitch_rad = 0.0;  // the camera's fixed pitch in the head (positive = nose down)
  double min_pan_rad = -1.62, max_pan_rad = 1.62;  // ERS-7: +-93 degrees
  double min_tilt_rad = -0.78, max_tilt_rad = 1.3;
  // The torso's pitch as the robot's inertial unit reads it (about y, positive = leaning forward,
  // as NAOqi's AngleY) when camera_pitch_rad was calibrated. A torso pitch read with an image then
  // gives the body's lean, which the head's joint sensors do not see: leanRad(). NaN: no reference
  // (the lean is 0 whatever the inertial unit reads).
  double torso_pitch_reference_rad = std::numeric_limits<double>::quiet_NaN();

  /// The body's lean at this torso pitch: torso_pitch_rad - torso_pitch_reference_rad; 0 without
  /// a reference or for a non-finite reading.
  double leanRad(double torso_pitch_rad) const {
    const double lean = torso_pitch_rad - torso_pitch_reference_rad;
    return std::isfinite(lean) ? lean : 0.0;
  }
  /// base_link -> head_pan_link; a body lean (leanRad()) turns the head about base_link's y axis
  /// at the pan axis (the neck), before the pan.
  Eigen::Isometry3d basePan(double pan_rad, double lean_rad = 0.0) const;
  Eigen::Isometry3d panTilt(double tilt_rad) const;  // head_pan_link -> head_tilt_link
  Eigen::Isometry3d tiltCamera() const;      // head_tilt_link -> camera_link (fixed; its pitch)
  static Eigen::Isometry3d cameraOptical();  // camera_link -> camera_optical_frame (fixed)
  /// base_link -> camera_optical_frame.
  Eigen::Isometry3d baseToOptical(double pan_rad, double tilt_rad, double lean_rad = 0.0) const;
  /// The angles are finite and inside the joints' ranges, up to 1e-3 rad over (a joint sensor may
  /// read a hair past its limit).
  bool inJointRange(double pan_rad, double tilt_rad) const {
    const auto inside = [](double v, double lo, double hi) {
      return std::isfinite(v) && v >= lo - 1e-3 && v <= hi + 1e-3;
    };
    return inside(pan_rad, min_pan_rad, max_pan_rad) &&
           inside(tilt_rad, min_tilt_rad, max_tilt_rad);
  }
};

/// The pitch of a body's orientation in a frame whose z axis is up (an inertial unit's): the angle
/// by which the body's x axis points below the horizontal (positive = leaning forward, about y, as
/// NAOqi's AngleY and HeadChain::torso_pitch_reference_rad); its yaw and roll do not change it.
double pitchBelowHorizontal(const Eigen::Quaterniond& orientation);

/// The 3-D pose of a planar base pose (map -> base_link), with optional body height/pitch/roll.
Eigen::Isometry3d planarToIsometry(const math::SE2& pose, double z_m = 0.0, double roll_rad = 0.0,
                                   double pitch_rad = 0.0);
/// The planar pose (x, y, yaw of the x axis projected on the ground) of a 3-D pose.
math::SE2 isometryToPlanar(const Eigen::Isometry3d& pose);

}  // namespace adaptive_perception::world
