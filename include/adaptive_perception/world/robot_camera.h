#pragma once
// A robot's camera as data (config/cameras/*.yaml): the image's intrinsics and the head chain that
// places the camera on the robot, with the names of the two head joints in joint_states.
//
// File format (every key at the top level; keys left out keep the AIBO ERS-7 defaults of
// PinholeCamera::aiboErs7() and HeadChain, which config/cameras/aibo_ers7.yaml writes out):
//   name: nao_v6_top
//   width_px: 640          height_px: 480
//   fx_px: 626.5           fy_px: 626.5        cx_px: 320.0       cy_px: 240.0
//   pan_joint: HeadYaw     tilt_joint: HeadPitch
//   base_to_pan_m: [x, y, z]       base_link (on the ground under the body) -> pan axis
//   pan_to_tilt_m: [x, y, z]       pan axis -> tilt axis
//   tilt_to_camera_m: [x, y, z]    tilt axis -> lens
//   camera_pitch_rad: 0.0          the lens's fixed pitch in the head (positive = nose down)
//   min_pan_rad, max_pan_rad, min_tilt_rad, max_tilt_rad: the joints' ranges
//   torso_pitch_reference_rad: -0.08  the inertial unit's torso pitch at the calibration (optional,
//                    default none: no lean; HeadChain::leanRad(): a torso pitch read later leans)
// Frames and signs are camera_model.h's (pan positive = left, tilt positive = nose down), which are
// the NAO's HeadYaw and HeadPitch. Errors name the file and line: a syntax error, an unknown key,
// a value of the wrong kind, a vector without three numbers, a camera that fails validate().
#include <string>

#include "adaptive_perception/world/camera_model.h"

namespace adaptive_perception::world {

struct RobotCamera {
  std::string name = "aibo_ers7";
  PinholeCamera camera = PinholeCamera::aiboErs7();
  HeadChain head;
  std::string pan_joint = "head_pan_joint";  // joint_states names of the head's joints
  std::string tilt_joint = "head_tilt_joint";

  /// base_link -> camera_optical_frame at these joint angles (the head chain alone).
  Eigen::Isometry3d baseToOptical(double pan_rad, double tilt_rad) const {
    return head.baseToOptical(pan_rad, tilt_rad);
  }
  /// The same, the head leaned by this torso pitch from the inertial unit (HeadChain::leanRad():
  /// its difference from torso_pitch_reference_rad; NaN, or no reference: no lean).
  Eigen::Isometry3d baseToOpticalAtTorsoPitch(double pan_rad, double tilt_rad,
                                              double torso_pitch_rad) const {
    return head.baseToOptical(pan_rad, tilt_rad, head.leanRad(torso_pitch_rad));
  }

  /// Reads a camera file; std::runtime_error "PATH:LINE: ..." on any error.
  static RobotCamera loadYaml(const std::string& path);
  static RobotCamera parseYaml(const std::string& yaml_text, const std::string& source_name);
};

}  // namespace adaptive_perception::world
