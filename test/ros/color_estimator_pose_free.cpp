// rostest: color_estimator with ~pose_free on the bundled bright bag, without a pose and then with
// one (color_estimator_pose_free.test).
#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include <cstdio>
#include <map>
#include <mutex>

#include "adaptive_perception/ColorModel.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/world/color_class.h"

namespace T = adaptive_perception::ros_topics;
namespace W = adaptive_perception::world;

namespace {

class ColorEstimatorPoseFree : public ::testing::Test {
 protected:
  void SetUp() override {
    ros::NodeHandle p("~");
    expected_frames_ = p.param("expected_frames", 33);
    frames_before_pose_ = p.param("pose_free_frames_before_pose", 8);
    relay_ = nh_.advertise<geometry_msgs::PoseStamped>("ground_truth/pose_after_start", 100);
    subs_.push_back(nh_.subscribe<geometry_msgs::PoseStamped>(
        T::kGroundTruthPose, 100, [this](const geometry_msgs::PoseStampedConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          // The ground truth goes through only once the node has classified frames without it.
          if (static_cast<int>(classified_.size()) >= frames_before_pose_) relay_.publish(m);
        }));
    subs_.push_back(nh_.subscribe<sensor_msgs::Image>(T::kCameraImage, 100,
                                                      [this](const sensor_msgs::ImageConstPtr&) {
                                                        std::lock_guard<std::mutex> l(mutex_);
                                                        ++images_;
                                                      }));
    subs_.push_back(nh_.subscribe<sensor_msgs::Image>(T::kCameraLabels, 100,
                                                      [this](const sensor_msgs::ImageConstPtr& m) {
                                                        std::lock_guard<std::mutex> l(mutex_);
                                                        truth_[m->header.stamp] = m;
                                                      }));
    subs_.push_back(nh_.subscribe<sensor_msgs::Image>("color_estimator/classified", 100,
                                                      [this](const sensor_msgs::ImageConstPtr& m) {
                                                        std::lock_guard<std::mutex> l(mutex_);
                                                        classified_[m->header.stamp] = m;
                                                      }));
    subs_.push_back(nh_.subscribe<adaptive_perception::ColorModel>(
        "color_estimator/color_model", 100,
        [this](const adaptive_perception::ColorModelConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          models_[m->header.stamp] = true;
        }));
    spinner_.start();
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(80.0);
    while (ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> l(mutex_);
        if (images_ >= expected_frames_) break;
      }
      ros::WallDuration(0.1).sleep();
    }
    ros::WallDuration(2.0).sleep();  // the last classified frame
  }

  ros::NodeHandle nh_;
  ros::AsyncSpinner spinner_{2};
  ros::Publisher relay_;
  std::vector<ros::Subscriber> subs_;
  std::mutex mutex_;
  int images_ = 0, expected_frames_ = 33, frames_before_pose_ = 8;
  std::map<ros::Time, sensor_msgs::ImageConstPtr> truth_, classified_;
  std::map<ros::Time, bool> models_;
};

TEST_F(ColorEstimatorPoseFree, ClassifiesWithoutAPoseThenHandsOver) {
  std::lock_guard<std::mutex> l(mutex_);
  ASSERT_EQ(images_, expected_frames_);
  int pose_free = 0, pose_driven = 0, pose_free_after = 0;
  long carpet = 0, carpet_as_field = 0, sky = 0, sky_as_background = 0;
  bool handed_over = false;
  for (const auto& [stamp, cls] : classified_) {
    ASSERT_TRUE(truth_.count(stamp)) << "a classified image with a stamp no input image had";
    ASSERT_EQ(cls->encoding, "mono8");
    const auto& t = truth_[stamp]->data;
    ASSERT_EQ(t.size(), cls->data.size());
    if (models_.count(stamp)) {  // pose-driven: a colour model came with it
      handed_over = true;
      ++pose_driven;
      continue;
    }
    // Pose-free frames hold field, line and background only. After the hand-over a frame whose
    // pose lookup timed out (a loaded machine) is classified without one, as designed: counted.
    if (handed_over) ++pose_free_after;
    ++pose_free;
    for (size_t i = 0; i < t.size(); ++i) {
      const std::uint8_t c = cls->data[i];
      ASSERT_TRUE(c == W::kGreen || c == W::kWhite || c == W::kBackground) << int(c);
      if (t[i] == W::kGreen) ++carpet, carpet_as_field += c == W::kGreen;
      if (t[i] == W::kBackground) ++sky, sky_as_background += c == W::kBackground;
    }
  }
  EXPECT_GE(pose_free, frames_before_pose_);
  EXPECT_GE(pose_driven, 10) << "the node did not hand over to the pose-driven update";
  ASSERT_GT(carpet, 0);
  ASSERT_GT(sky, 0);
  // The hand-over holds: after the first pose-driven frame, most frames are pose-driven.
  EXPECT_LT(pose_free_after, pose_driven / 4) << pose_free_after << " pose-free frames after it";
  const double carpet_rate = double(carpet_as_field) / carpet;
  const double sky_rate = double(sky_as_background) / sky;
  std::printf("color_estimator_pose_free: pose_free=%d pose_driven=%d carpet_as_field=%.3f "
              "background_as_background=%.3f\n",
              pose_free, pose_driven, carpet_rate, sky_rate);
  EXPECT_GE(carpet_rate, 0.9);
  EXPECT_GE(sky_rate, 0.8);
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "color_estimator_pose_free_test");
  return RUN_ALL_TESTS();
}
