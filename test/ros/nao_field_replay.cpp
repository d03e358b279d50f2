// rostest: one point of the real NAO field development set through head_tf_publisher,
// color_estimator and rbpf_localizer (nao_field_replay.test).
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <cmath>
#include <cstdio>
#include <mutex>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/world/color_class.h"

using namespace adaptive_perception;
namespace T = adaptive_perception::ros_topics;

namespace {

// Shares of a class-id image's rows [top, bottom) (fractions of its height) labelled `cls`.
double classShare(const sensor_msgs::Image& labels, double top, double bottom, std::uint8_t cls) {
  const int r0 = static_cast<int>(top * labels.height);
  const int r1 = static_cast<int>(bottom * labels.height);
  long n = 0, hit = 0;
  for (int r = r0; r < r1; ++r)
    for (std::uint32_t c = 0; c < labels.width; ++c, ++n)
      hit += labels.data[r * labels.step + c] == cls;
  return n ? static_cast<double>(hit) / n : 0.0;
}

class NaoFieldReplay : public ::testing::Test {
 protected:
  void SetUp() override {
    ros::NodeHandle p("~");
    expected_frames_ = p.param("expected_frames", 120);
    subs_.push_back(nh_.subscribe<sensor_msgs::CameraInfo>(
        T::kCameraInfo, 200, [this](const sensor_msgs::CameraInfoConstPtr&) {
          std::lock_guard<std::mutex> l(mutex_);
          ++infos_;
        }));
    subs_.push_back(nh_.subscribe<geometry_msgs::PoseWithCovarianceStamped>(
        "rbpf_localizer/pose", 200,
        [this](const geometry_msgs::PoseWithCovarianceStampedConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          ++poses_;
          last_pose_ = m;
        }));
    subs_.push_back(nh_.subscribe<sensor_msgs::Image>(
        "color_estimator/classified", 200, [this](const sensor_msgs::ImageConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          ++classified_;
          last_classified_ = m;
        }));
    spinner_.start();
    // The player makes the bag (a few seconds) and plays it in step with the localizer; wait
    // (wall time) for every frame, then for the nodes to answer the last.
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(200.0);
    while (ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> l(mutex_);
        if (infos_ >= expected_frames_) break;
      }
      ros::WallDuration(0.1).sleep();
    }
    ros::WallDuration(3.0).sleep();
  }
  void TearDown() override {  // no callback may run on the members after this
    spinner_.stop();
    subs_.clear();
  }

  ros::NodeHandle nh_;
  ros::AsyncSpinner spinner_{2};
  std::vector<ros::Subscriber> subs_;
  tf2_ros::Buffer tf_buffer_{ros::Duration(60.0)};
  tf2_ros::TransformListener tf_listener_{tf_buffer_};
  std::mutex mutex_;
  int expected_frames_ = 120, infos_ = 0, poses_ = 0, classified_ = 0;
  geometry_msgs::PoseWithCovarianceStampedConstPtr last_pose_;
  sensor_msgs::ImageConstPtr last_classified_;
};

TEST_F(NaoFieldReplay, LocalizerHoldsThePointAndTheFieldIsClassified) {
  ros::NodeHandle p("~");
  const double x = p.param("x_m", 0.0), y = p.param("y_m", 0.0), yaw = p.param("yaw_rad", 0.0);
  const double max_error_m = p.param("max_position_error_m", 0.5);
  const double max_heading_deg = p.param("max_heading_error_deg", 10.0);
  std::lock_guard<std::mutex> l(mutex_);
  ASSERT_EQ(infos_, expected_frames_) << "the player did not play the whole bag";

  // The head chain from joint_states (head_tf_publisher) reaches the images' frame.
  EXPECT_TRUE(tf_buffer_.canTransform(T::kBaseFrame, T::kCameraOpticalFrame, ros::Time(0)));

  // The localizer answered (nearly) every image in step and holds the point.
  EXPECT_GE(poses_, expected_frames_ - 2);
  ASSERT_TRUE(last_pose_);
  EXPECT_EQ(last_pose_->header.frame_id, T::kMapFrame);
  const math::SE2 est = ros_conv::toSE2(last_pose_->pose.pose);
  const double error_m = std::hypot(est.x_m - x, est.y_m - y);
  const double heading_deg = math::radToDeg(std::abs(math::angleDiff(est.yaw_rad, yaw)));
  std::printf(
      "nao_field_replay: poses=%d classified=%d position_error_m=%.3f heading_error_deg=%.1f\n",
      poses_, classified_, error_m, heading_deg);
  EXPECT_LE(error_m, max_error_m);
  EXPECT_LE(heading_deg, max_heading_deg);

  // color_estimator classified the images (not in step: it may drop some): carpet fills the
  // bottom of every development view and the room the top.
  EXPECT_GE(classified_, 10);
  ASSERT_TRUE(last_classified_);
  ASSERT_EQ(last_classified_->encoding, "mono8");
  const double field_bottom = classShare(*last_classified_, 0.67, 1.0, world::kGreen);
  const double field_top = classShare(*last_classified_, 0.0, 0.2, world::kGreen);
  const double lines_bottom = classShare(*last_classified_, 0.5, 1.0, world::kWhite);
  std::printf("nao_field_replay: field share bottom third %.3f, top fifth %.3f; line share "
              "bottom half %.3f\n", field_bottom, field_top, lines_bottom);
  EXPECT_GE(field_bottom, 0.6);
  EXPECT_LE(field_top, 0.1);
  EXPECT_GT(lines_bottom, 0.005);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "nao_field_replay");
  return RUN_ALL_TESTS();
}
