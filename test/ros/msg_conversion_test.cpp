// Message conversion on hostile input, without a master (ros/msg_conversion.h, ros/image_gate.h):
// image sizes whose byte counts wrap in 32 bits, images over the pixel limit, and the one reading
// of a pose-with-covariance input that initialpose and external_pose share.
#include "adaptive_perception/ros/msg_conversion.h"

#include <gtest/gtest.h>
#include <ros/time.h>
#include <sensor_msgs/image_encodings.h>

#include <cmath>
#include <limits>
#include <string>

#include "../core/refusal.h"
#include "adaptive_perception/ros/image_gate.h"

using namespace adaptive_perception;
using ros_conv::ImageFormatError;

namespace {

sensor_msgs::Image image(const std::string& encoding, std::uint32_t width, std::uint32_t height,
                         std::uint32_t step, std::size_t bytes) {
  sensor_msgs::Image m;
  m.header.stamp = ros::Time(10, 0);
  m.encoding = encoding;
  m.width = width;
  m.height = height;
  m.step = step;
  m.data.assign(bytes, 128);
  return m;
}

/// The message of the ImageFormatError `f` throws, or "accepted" / "other exception".
template <class F>
std::string imageError(F f) {
  try {
    f();
  } catch (const ImageFormatError& e) {
    return e.what();
  } catch (...) {
    return "other exception";
  }
  return "accepted";
}

/// Passes when `f` throws ImageFormatError naming `what`.
template <class F>
::testing::AssertionResult imageRefused(F f, const std::string& what) {
  const std::string message = imageError(f);
  if (message.find(what) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "expected an ImageFormatError naming '" << what << "', got: " << message;
}

geometry_msgs::PoseWithCovariance rvizPose() {
  geometry_msgs::PoseWithCovariance p;
  p.pose.position.x = 1.0;
  p.pose.position.y = -2.0;
  p.pose.orientation.z = std::sin(0.25);
  p.pose.orientation.w = std::cos(0.25);  // yaw 0.5 rad
  p.covariance[0] = p.covariance[7] = 0.25;
  p.covariance[35] = 0.068;
  return p;
}

/// Passes when planarPoseInput refuses `p` naming `what`.
::testing::AssertionResult poseRefused(const geometry_msgs::PoseWithCovariance& p,
                                       ros_conv::PoseYaw yaw, const std::string& what) {
  return test_support::refusedNaming([&] { ros_conv::planarPoseInput(p, yaw); }, what);
}

}  // namespace

// A bgr8 width of 1431655766 makes width x 3 = 4294967298, which is 2 in 32 bits: step 2 and two
// bytes of data passed the check, and the conversion read past the buffer or threw cv::Exception.
TEST(MsgConversion, ImageSizesThatWrapIn32BitsAreRefused) {
  const sensor_msgs::Image wrap = image("bgr8", 1431655766u, 1, 2, 2);
  EXPECT_TRUE(imageRefused([&] { ros_conv::imageToBgr8(wrap); }, "more than the limit"));
  EXPECT_TRUE(imageRefused([&] { ros_conv::imageToYuv(wrap); }, "more than the limit"));
  // With no pixel limit at all, the 64-bit row size still refuses it.
  EXPECT_TRUE(
      imageRefused([&] { ros_conv::imageToBgr8(wrap, std::numeric_limits<std::int64_t>::max()); },
                   "buffer too small"));
  // A yuv422 width of 0x80000002 became a negative column count.
  const sensor_msgs::Image yuv = image("yuv422", 0x80000002u, 1, 4, 4);
  EXPECT_TRUE(imageRefused([&] { ros_conv::imageToYuv(yuv); }, "more than the limit"));
  EXPECT_TRUE(
      imageRefused([&] { ros_conv::imageToYuv(yuv, std::numeric_limits<std::int64_t>::max()); },
                   "buffer too small"));
  const sensor_msgs::Image mono = image("mono8", 0xffffffffu, 0xffffffffu, 0xffffffffu, 16);
  EXPECT_TRUE(imageRefused([&] { ros_conv::imageToMono8(mono); }, "more than the limit"));
  // A good image at the limit passes, one pixel over it does not.
  const sensor_msgs::Image good = image("bgr8", 40, 30, 120, 3600);
  EXPECT_EQ(imageError([&] { ros_conv::imageToBgr8(good, 1200); }), "accepted");
  EXPECT_TRUE(imageRefused([&] { ros_conv::imageToBgr8(good, 1199); }, "1200 pixels"));
}

// The gate every camera node takes its images through counts such an image as bad and throws
// nothing, whatever the conversion throws.
TEST(MsgConversion, ImageGateDropsWhatCannotBeConverted) {
  ros::Time::init();
  ros_conv::ImageIntakeConfig intake;
  intake.max_pixels = 1000;
  ros_conv::ImageGate gate("test", 0.0, intake, ros_conv::ImageGate::Output::kYuv);
  cv::Mat out;
  sensor_msgs::Image wrap = image("bgr8", 1431655766u, 1, 2, 2);
  EXPECT_FALSE(gate.admit(wrap, &out));
  sensor_msgs::Image big = image("bgr8", 40, 30, 120, 3600);  // 1200 pixels
  big.header.stamp = ros::Time(11, 0);
  EXPECT_FALSE(gate.admit(big, &out));
  EXPECT_EQ(gate.badImages(), 2);
  sensor_msgs::Image small = image("bgr8", 20, 30, 60, 1800);
  small.header.stamp = ros::Time(12, 0);
  EXPECT_TRUE(gate.admit(small, &out));
  EXPECT_EQ(out.cols, 20);
}

// initialpose and external_pose: a cross term written on one side only (covariance[30], yaw-x),
// a NaN cross term, a NaN position, a zero quaternion and a covariance that is not positive
// definite are each refused naming what is wrong; rviz's pose is read as it was sent.
TEST(MsgConversion, PoseWithCovarianceInputIsCheckedOneWay) {
  using ros_conv::PoseYaw;
  const ros_conv::PlanarPoseInput ok = ros_conv::planarPoseInput(rvizPose(), PoseYaw::kRequired);
  EXPECT_NEAR(ok.pose.x_m, 1.0, 1e-12);
  EXPECT_NEAR(ok.pose.y_m, -2.0, 1e-12);
  EXPECT_NEAR(ok.pose.yaw_rad, 0.5, 1e-12);
  EXPECT_TRUE(ok.cov.isApprox(Eigen::Vector3d(0.25, 0.25, 0.068).asDiagonal().toDenseMatrix()));
  EXPECT_TRUE(ok.has_yaw);

  for (PoseYaw yaw : {PoseYaw::kRequired, PoseYaw::kIfKnown}) {
    geometry_msgs::PoseWithCovariance p = rvizPose();
    p.covariance[30] = 10.0;
    EXPECT_TRUE(poseRefused(p, yaw, "(x, y, yaw) covariance is not symmetric"));
    p = rvizPose();
    p.covariance[30] = std::nan("");
    EXPECT_TRUE(poseRefused(p, yaw, "NaN"));
    p = rvizPose();
    p.pose.position.x = std::nan("");
    EXPECT_TRUE(poseRefused(p, yaw, "position"));
    p = rvizPose();
    p.pose.orientation.z = p.pose.orientation.w = 0.0;
    EXPECT_TRUE(poseRefused(p, yaw, "quaternion"));
    // Symmetric to 1e-9 and positive definite in its lower triangle, but not once symmetrised:
    // what is returned must be what was checked.
    p = rvizPose();
    p.covariance[6] = 0.25 - 1e-13;
    p.covariance[1] = p.covariance[6] + 2e-10;
    EXPECT_TRUE(poseRefused(p, yaw, "not positive definite"));
    p = rvizPose();
    p.covariance[1] = p.covariance[6] = 1.0;
    EXPECT_TRUE(poseRefused(p, yaw, "(x, y"));
    EXPECT_TRUE(poseRefused(p, yaw, "not positive definite"));
  }
  // external_pose without a heading: yaw variance at or above the "unknown" level, or infinite,
  // gives a position fix whose cross terms with yaw are not read.
  geometry_msgs::PoseWithCovariance p = rvizPose();
  p.covariance[35] = std::numeric_limits<double>::infinity();
  p.covariance[5] = p.covariance[30] = std::numeric_limits<double>::infinity();
  const ros_conv::PlanarPoseInput position = ros_conv::planarPoseInput(p, PoseYaw::kIfKnown);
  EXPECT_FALSE(position.has_yaw);
  const Eigen::Matrix2d position_cov = position.cov.topLeftCorner<2, 2>();
  EXPECT_TRUE(position_cov.isApprox(0.25 * Eigen::Matrix2d::Identity()));
  EXPECT_TRUE(poseRefused(p, PoseYaw::kRequired, "not finite"));
  p.covariance[35] = ros_conv::kUnknownYawVariance;
  p.covariance[5] = p.covariance[30] = 0.0;
  EXPECT_FALSE(ros_conv::planarPoseInput(p, PoseYaw::kIfKnown).has_yaw);
}
