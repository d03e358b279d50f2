// RobotCamera: the camera files against the built-in AIBO camera and against the NAO's chain
// computed by hand; errors name the file and line.
#include "adaptive_perception/world/robot_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace adaptive_perception::world {
namespace {

const std::string kDir = std::string(AP_SOURCE_DIR) + "/config/cameras/";

std::string errorOf(const std::string& yaml) {
  try {
    RobotCamera::parseYaml(yaml, "cam.yaml");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(RobotCamera, AiboFileIsTheBuiltInCamera) {
  const RobotCamera file = RobotCamera::loadYaml(kDir + "aibo_ers7.yaml");
  const PinholeCamera built_in = PinholeCamera::aiboErs7();
  EXPECT_EQ(file.camera.width_px, built_in.width_px);
  EXPECT_EQ(file.camera.height_px, built_in.height_px);
  EXPECT_NEAR(file.camera.fx_px, built_in.fx_px, 1e-9);
  EXPECT_NEAR(file.camera.fy_px, built_in.fy_px, 1e-9);
  EXPECT_EQ(file.camera.cx_px, built_in.cx_px);
  EXPECT_EQ(file.camera.cy_px, built_in.cy_px);
  const HeadChain head;
  for (const double pan : {-1.0, 0.0, 0.7})
    for (const double tilt : {-0.5, 0.0, 0.4})
      EXPECT_TRUE(file.baseToOptical(pan, tilt).isApprox(head.baseToOptical(pan, tilt), 1e-12));
}

TEST(RobotCamera, NaoTopChainByHand) {
  const RobotCamera nao = RobotCamera::loadYaml(kDir + "nao_v6_top.yaml");
  EXPECT_EQ(nao.pan_joint, "HeadYaw");
  EXPECT_EQ(nao.tilt_joint, "HeadPitch");
  EXPECT_EQ(nao.camera.width_px, 640);
  const double pitch = 0.1;  // head pitch; the lens's own pitch adds to it
  const double total = pitch + nao.head.camera_pitch_rad;
  const double z_pan = nao.head.base_to_pan_m.z();
  // Looking straight ahead, pitched down by `total`: the lens sits 0.05871 m ahead of and 0.06364 m
  // above the pitch axis, rotated with it; the optical axis points forward and down.
  const Eigen::Isometry3d t = nao.baseToOptical(0.0, pitch);
  EXPECT_NEAR(t.translation().x(), 0.05871 * std::cos(pitch) + 0.06364 * std::sin(pitch), 1e-12);
  EXPECT_NEAR(t.translation().y(), 0.0, 1e-12);
  EXPECT_NEAR(t.translation().z(), z_pan + 0.06364 * std::cos(pitch) - 0.05871 * std::sin(pitch),
              1e-12);
  const Eigen::Vector3d axis = t.linear().col(2);  // optical z
  EXPECT_NEAR(axis.x(), std::cos(total), 1e-12);
  EXPECT_NEAR(axis.z(), -std::sin(total), 1e-12);
  EXPECT_NEAR(t.linear().col(0).y(), -1.0, 1e-12);  // optical x (image right) = robot's right
  // Yaw 90 degrees left: the lens is on the robot's left, looking left.
  const Eigen::Isometry3d left = nao.baseToOptical(M_PI / 2, 0.0);
  EXPECT_NEAR(left.translation().y(), 0.05871, 1e-12);
  EXPECT_NEAR(left.linear().col(2).y(), std::cos(nao.head.camera_pitch_rad), 1e-12);
  // The bottom camera looks further down than the top one by the published 0.6929 - 0.0209.
  const RobotCamera bottom = RobotCamera::loadYaml(kDir + "nao_v6_bottom.yaml");
  EXPECT_NEAR(bottom.head.camera_pitch_rad - nao.head.camera_pitch_rad, 0.672, 1e-9);
}

TEST(RobotCamera, TorsoPitchLeansTheHeadAboutTheNeckByHand) {
  RobotCamera nao = RobotCamera::parseYaml(
      "base_to_pan_m: [0, 0, 0.35]\npan_to_tilt_m: [0, 0, 0]\ntilt_to_camera_m: [0.05, 0, 0.06]\n"
      "camera_pitch_rad: 0.0\ntorso_pitch_reference_rad: -0.08\n",
      "cam.yaml");
  EXPECT_DOUBLE_EQ(nao.head.torso_pitch_reference_rad, -0.08);
  // Leaning forward by 0.1 rad (the inertial unit reads 0.02): the lens turns about the neck,
  // 0.35 m up, and the optical axis points down by the lean plus the head's pitch.
  const double lean = 0.1, pitch = 0.05;
  EXPECT_NEAR(nao.head.leanRad(0.02), lean, 1e-15);
  const Eigen::Isometry3d t = nao.baseToOpticalAtTorsoPitch(0.0, pitch, 0.02);
  const double a = lean + pitch;
  EXPECT_NEAR(t.translation().x(), 0.05 * std::cos(a) + 0.06 * std::sin(a), 1e-12);
  EXPECT_NEAR(t.translation().z(), 0.35 + 0.06 * std::cos(a) - 0.05 * std::sin(a), 1e-12);
  EXPECT_NEAR(t.linear().col(2).x(), std::cos(a), 1e-12);
  EXPECT_NEAR(t.linear().col(2).z(), -std::sin(a), 1e-12);
  // Looking left (yaw 90 degrees), the forward lean still tilts the view down, not sideways.
  const Eigen::Isometry3d left = nao.baseToOpticalAtTorsoPitch(M_PI / 2, 0.0, 0.02);
  EXPECT_NEAR(left.linear().col(2).y(), 1.0, 1e-12);
  EXPECT_NEAR(left.linear().col(0).z(), -std::sin(lean), 1e-12);  // image right (forward) is lower
  // No reading, or no reference: no lean.
  const double none = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(nao.baseToOpticalAtTorsoPitch(0.3, pitch, none)
                  .isApprox(nao.head.baseToOptical(0.3, pitch), 1e-15));
  nao.head.torso_pitch_reference_rad = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(nao.head.leanRad(0.02), 0.0);
  EXPECT_TRUE(nao.baseToOpticalAtTorsoPitch(0.3, pitch, 0.02)
                  .isApprox(nao.head.baseToOptical(0.3, pitch), 1e-15));
}

TEST(RobotCamera, PitchBelowHorizontalIgnoresYawAndRoll) {
  using Eigen::AngleAxisd;
  using Eigen::Vector3d;
  for (const double pitch : {-0.142, 0.0, 0.008, 0.3})
    for (const double yaw : {0.0, 0.516, -2.5})
      for (const double roll : {0.0, -0.0188, 0.2}) {
        // Yaw, then pitch, then roll (NAOqi's AngleZ, AngleY, AngleX), not normalised on purpose.
        const Eigen::Quaterniond q(AngleAxisd(yaw, Vector3d::UnitZ()) *
                                   AngleAxisd(pitch, Vector3d::UnitY()) *
                                   AngleAxisd(roll, Vector3d::UnitX()));
        EXPECT_NEAR(pitchBelowHorizontal(Eigen::Quaterniond(q.coeffs() * 3.0)), pitch, 1e-12);
      }
  // A positive pitch is a forward lean: the body's x axis, turned about +y, points down.
  EXPECT_LT((AngleAxisd(0.1, Vector3d::UnitY()) * Vector3d::UnitX()).z(), 0.0);
}

TEST(RobotCamera, ErrorsNameTheFileLineAndKey) {
  EXPECT_NE(errorOf("name: x\ncamera_pitch_rad: 7\n")
                .find("cam.yaml:2: 'camera_pitch_rad' must be within a full turn"),
            std::string::npos);
  EXPECT_NE(errorOf("tilt_to_camera_m: [58.71, 0, 63.64]\n")
                .find("cam.yaml:1: 'tilt_to_camera_m' has an offset beyond 10 m"),
            std::string::npos);
  EXPECT_NE(errorOf("torso_pitch_reference_rad: .inf\n")
                .find("cam.yaml:1: 'torso_pitch_reference_rad' must be finite"),
            std::string::npos);
  EXPECT_NE(errorOf("name: x\nfocal: 3\n").find("cam.yaml:2: unknown key 'focal'"),
            std::string::npos);
  EXPECT_NE(errorOf("fx_px: [1, 2]\n").find("cam.yaml:1: bad value for 'fx_px'"),
            std::string::npos);
  EXPECT_NE(errorOf("name: x\nbase_to_pan_m: [0, 1]\n").find("cam.yaml:2: 'base_to_pan_m' needs"),
            std::string::npos);
  EXPECT_NE(errorOf("fx_px: .nan\n").find("cam.yaml:1: 'fx_px' must be finite"), std::string::npos);
  EXPECT_NE(errorOf("width_px: 640\nheight_px: 480\n").find("without fx_px"), std::string::npos);
  EXPECT_NE(errorOf("fx_px: -3\n").find("focal lengths must be positive"), std::string::npos);
  EXPECT_NE(errorOf("min_pan_rad: 2\nmax_pan_rad: 1\n").find("min_*_rad is above"),
            std::string::npos);
  EXPECT_NE(errorOf("").find("no camera in the file"), std::string::npos);
  EXPECT_NE(errorOf("[1, 2]").find("expected a map"), std::string::npos);
  EXPECT_NE(errorOf("a: [1,\n").find("YAML syntax error"), std::string::npos);
  try {
    RobotCamera::loadYaml("/nonexistent/camera.yaml");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/camera.yaml: cannot open"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace adaptive_perception::world
