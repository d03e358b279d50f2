// rostest: color_estimator on the bundled switching bag.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <mutex>

#include "adaptive_perception/ColorModel.h"
#include "adaptive_perception/LightingState.h"
#include "adaptive_perception/SavePrior.h"
#include "adaptive_perception/color/color_model.h"
#include "adaptive_perception/ros/topics.h"

namespace T = adaptive_perception::ros_topics;
using adaptive_perception::ColorModel;
using adaptive_perception::LightingState;

namespace {

class ColorEstimatorSwitching : public ::testing::Test {
 protected:
  void SetUp() override {
    ros::NodeHandle p("~");
    expected_frames_ = p.param("expected_frames", 49);
    min_rate_ = p.param("min_overall_rate", 0.95);
    subs_.push_back(nh_.subscribe<sensor_msgs::Image>(T::kCameraImage, 100,
                                                      [this](const sensor_msgs::ImageConstPtr& m) {
                                                        std::lock_guard<std::mutex> l(mutex_);
                                                        ++images_;
                                                        image_stamps_[m->header.stamp] = true;
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
    subs_.push_back(nh_.subscribe<ColorModel>(
        "color_estimator/color_model", 100, [this](const adaptive_perception::ColorModelConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          models_[m->header.stamp] = m;
        }));
    subs_.push_back(nh_.subscribe<LightingState>(
        T::kLightingState, 100, [this](const adaptive_perception::LightingStateConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          lighting_[m->header.stamp] = m->condition;
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
  std::vector<ros::Subscriber> subs_;
  std::mutex mutex_;
  int images_ = 0, expected_frames_ = 49;
  double min_rate_ = 0.95;
  std::map<ros::Time, bool> image_stamps_;
  std::map<ros::Time, sensor_msgs::ImageConstPtr> truth_, classified_;
  std::map<ros::Time, adaptive_perception::ColorModelConstPtr> models_;
  std::map<ros::Time, std::string> lighting_;
};

TEST_F(ColorEstimatorSwitching, ClassifiesThroughLightChangesAndServes) {
  std::lock_guard<std::mutex> l(mutex_);
  ASSERT_EQ(images_, expected_frames_);
  // Every frame but possibly the first (whose tf may not be there yet) is classified, with its
  // stamp.
  EXPECT_GE(static_cast<int>(classified_.size()), expected_frames_ - 2);
  long correct = 0, total = 0;
  int dark_frames = 0, dark_selected = 0;
  for (const auto& [stamp, cls] : classified_) {
    ASSERT_TRUE(image_stamps_.count(stamp))
        << "classified image carries a stamp no input image had";
    ASSERT_TRUE(truth_.count(stamp));
    EXPECT_EQ(cls->encoding, "mono8");
    const auto& t = truth_[stamp]->data;
    ASSERT_EQ(t.size(), cls->data.size());
    for (size_t i = 0; i < t.size(); ++i) {
      if (t[i] > 4) continue;  // background and unmodelled classes are not scored
      ++total;
      correct += t[i] == cls->data[i];
    }
    ASSERT_TRUE(models_.count(stamp));
    const auto& m = *models_[stamp];
    ASSERT_EQ(m.color_names.size(), 5u);
    ASSERT_EQ(m.mean.size(), 15u);
    ASSERT_EQ(m.covariance.size(), 225u);
    ASSERT_EQ(m.mode_names.size(), 2u);
    double sum = 0;
    for (double p : m.mode_probabilities) sum += p;
    EXPECT_NEAR(sum, 1.0, 1e-9);
    // Mode selection follows the light (allow the frame at a switch to lag).
    if (lighting_.count(stamp) && lighting_[stamp] == "dark") {
      ++dark_frames;
      dark_selected += m.mode_names[m.active_mode] == "dark";
    }
  }
  ASSERT_GT(total, 0);
  const double rate = static_cast<double>(correct) / total;
  EXPECT_GE(rate, min_rate_) << "overall classification rate";
  ASSERT_GT(dark_frames, 5);
  EXPECT_GE(dark_selected, dark_frames - 4)
      << "the dark mode should be active while the lights are off";
  std::printf("color_estimator_switching: overall_rate=%.3f dark_frames=%d dark_selected=%d\n",
              rate, dark_frames, dark_selected);

  // Services.
  std_srvs::Trigger reset;
  ASSERT_TRUE(ros::service::call("/color_estimator/reset", reset));
  EXPECT_TRUE(reset.response.success);
  const std::string path =
      ::testing::TempDir() + "/saved_prior_" + std::to_string(::getpid()) + ".yaml";
  std::filesystem::remove(path);
  adaptive_perception::SavePrior save;
  save.request.path = path;
  ASSERT_TRUE(ros::service::call("/color_estimator/save_prior", save));
  EXPECT_TRUE(save.response.success) << save.response.message;
  EXPECT_NO_THROW(adaptive_perception::color::LightingPrior::loadYaml(path));
  ASSERT_TRUE(ros::service::call("/color_estimator/save_prior", save));
  EXPECT_FALSE(save.response.success)
      << "an existing file must not be overwritten without overwrite";
  std::filesystem::remove(path);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "color_estimator_switching");
  return RUN_ALL_TESTS();
}
