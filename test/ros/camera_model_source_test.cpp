// The camera model of the image nodes (ros/camera_model_source.h), without a master: no camera
// without camera_info unless ~camera_model names one (the AIBO, or a camera file), and a distorted camera_info's images
// rectified so that a point lands where the plumb_bob model, written out by hand, says.
#include "adaptive_perception/ros/camera_model_source.h"

#include <gtest/gtest.h>
#include <ros/time.h>

#include <opencv2/imgproc.hpp>

using adaptive_perception::ros_conv::CameraModelSource;

namespace {

sensor_msgs::CameraInfo info(const std::vector<double>& d) {
  sensor_msgs::CameraInfo c;
  c.width = 320;
  c.height = 240;
  c.distortion_model = "plumb_bob";
  c.D = d;
  c.K = {250.0, 0.0, 160.0, 0.0, 250.0, 120.0, 0.0, 0.0, 1.0};
  c.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  c.P = {250.0, 0.0, 160.0, 0.0, 0.0, 250.0, 120.0, 0.0, 0.0, 0.0, 1.0, 0.0};
  return c;
}

}  // namespace

TEST(CameraModelSource, WaitsForCameraInfoUnlessACameraIsNamed) {
  ros::Time::init();  // the throttled log messages read the clock
  CameraModelSource waiting("test", "");
  EXPECT_FALSE(waiting.readyFor(208, 160));
  EXPECT_FALSE(waiting.known());
  CameraModelSource aibo("test", "aibo_ers7");
  EXPECT_TRUE(aibo.readyFor(208, 160));
  EXPECT_FALSE(CameraModelSource("test", "aibo_ers7").readyFor(320, 240));
  try {
    CameraModelSource bad("test", "ers210");
    FAIL() << "accepted camera_model ers210";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("camera_model"), std::string::npos) << e.what();
  }
  // A camera file (relative: from the package): its intrinsics, for its image size only.
  CameraModelSource nao("test", "config/cameras/nao_v6_top.yaml");
  EXPECT_FALSE(nao.readyFor(208, 160));
  EXPECT_TRUE(nao.readyFor(640, 480));
  EXPECT_DOUBLE_EQ(nao.camera().fx_px, 625.5);
  EXPECT_THROW(CameraModelSource("test", "/nonexistent/camera.yaml"), std::runtime_error);
  EXPECT_TRUE(waiting.onCameraInfo(info({0, 0, 0, 0, 0})));
  EXPECT_TRUE(waiting.readyFor(320, 240));
  EXPECT_FALSE(waiting.readyFor(208, 160));                   // the size disagrees with camera_info
  EXPECT_FALSE(waiting.onCameraInfo(info({0, 0, 0, 0, 0})));  // the same camera again
}

TEST(CameraModelSource, RectifiesAsThePlumbBobModelSays) {
  ros::Time::init();
  const double k1 = -0.25, k2 = 0.06, fx = 250.0, cx = 160.0, cy = 120.0;
  CameraModelSource source("test", "");
  ASSERT_TRUE(source.onCameraInfo(info({k1, k2, 0, 0, 0})));
  EXPECT_DOUBLE_EQ(source.camera().fx_px, fx);  // the rectified camera: P
  for (const cv::Point2d rect :
       {cv::Point2d(60, 40), cv::Point2d(280, 200), cv::Point2d(250, 60)}) {
    // Where the lens puts the rectified point: x_d = x (1 + k1 r^2 + k2 r^4).
    const double x = (rect.x - cx) / fx, y = (rect.y - cy) / fx, r2 = x * x + y * y;
    const double f = 1.0 + k1 * r2 + k2 * r2 * r2;
    const cv::Point2d raw(fx * x * f + cx, fx * y * f + cy);
    cv::Mat image(240, 320, CV_8UC3, cv::Scalar(0, 0, 0));
    cv::circle(
        image,
        cv::Point(static_cast<int>(std::lround(raw.x)), static_cast<int>(std::lround(raw.y))), 2,
        cv::Scalar(255, 255, 255), cv::FILLED);
    cv::Mat grey;
    cv::cvtColor(source.rectify(image), grey, cv::COLOR_BGR2GRAY);
    const cv::Moments m = cv::moments(grey);
    ASSERT_GT(m.m00, 0.0);
    const cv::Point2d found(m.m10 / m.m00, m.m01 / m.m00);
    EXPECT_NEAR(found.x, rect.x, 1.0) << "raw " << raw;
    EXPECT_NEAR(found.y, rect.y, 1.0) << "raw " << raw;
  }
}
