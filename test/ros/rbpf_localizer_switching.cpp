// rostest: rbpf_localizer on a bag from a global start (rbpf_localizer_switching.test: the bundled
// switching bag; rbpf_localizer_kidnap.test: a simulated kidnap), checked against its ground truth.
#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <cmath>
#include <map>
#include <mutex>

#include "adaptive_perception/ColorModel.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/topics.h"

namespace T = adaptive_perception::ros_topics;
namespace conv = adaptive_perception::ros_conv;

namespace {

class RbpfLocalizerSwitching : public ::testing::Test {
 protected:
  void SetUp() override {
    ros::NodeHandle p("~");
    max_pos_m_ = p.param("max_final_position_error_m", 0.2);
    max_head_deg_ = p.param("max_final_heading_error_deg", 10.0);
    subs_.push_back(nh_.subscribe<geometry_msgs::PoseStamped>(
        T::kGroundTruthPose, 200, [this](const geometry_msgs::PoseStampedConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          truth_[m->header.stamp] = m->pose;
        }));
    subs_.push_back(nh_.subscribe<geometry_msgs::PoseWithCovarianceStamped>(
        "rbpf_localizer/pose", 200,
        [this](const geometry_msgs::PoseWithCovarianceStampedConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          estimates_[m->header.stamp] = m;
          last_estimate_wall_ = ros::WallTime::now();
        }));
    subs_.push_back(nh_.subscribe<geometry_msgs::PoseArray>(
        "rbpf_localizer/particles", 10, [this](const geometry_msgs::PoseArrayConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          particles_ = m->poses.size();
          particles_frame_ = m->header.frame_id;
        }));
    subs_.push_back(nh_.subscribe<adaptive_perception::ColorModel>(
        "rbpf_localizer/color_model", 10, [this](const adaptive_perception::ColorModelConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          model_ = m;
        }));
    spinner_.start();
    // Until the bag is over: estimates stop arriving for 15 s of wall time after at least one. The
    // lockstep player waits up to its timeout_s (10 s) for the answer to each image before it
    // sends the next, so a quiet spell shorter than that is one slow frame (a global search on a
    // loaded machine), not the end of the bag.
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(120.0);
    while (ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> l(mutex_);
        if (!estimates_.empty() &&
            ros::WallTime::now() - last_estimate_wall_ > ros::WallDuration(15.0))
          break;
      }
      ros::WallDuration(0.2).sleep();
    }
  }

  ros::NodeHandle nh_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_{tf_buffer_};
  ros::AsyncSpinner spinner_{2};
  std::vector<ros::Subscriber> subs_;
  std::mutex mutex_;
  std::map<ros::Time, geometry_msgs::Pose> truth_;
  std::map<ros::Time, geometry_msgs::PoseWithCovarianceStampedConstPtr> estimates_;
  ros::WallTime last_estimate_wall_;
  size_t particles_ = 0;
  std::string particles_frame_;
  adaptive_perception::ColorModelConstPtr model_;
  double max_pos_m_ = 0.2, max_head_deg_ = 10.0;
};

// One test: the bag is replayed once.
TEST_F(RbpfLocalizerSwitching, GlobalStartConvergesAndPublishesEverything) {
  std::unique_lock<std::mutex> lock(mutex_);
  ASSERT_GE(estimates_.size(), 10u) << "too few pose estimates: did the node process the bag?";
  // The last estimate that has a ground-truth pose at the same stamp.
  const geometry_msgs::Pose* truth = nullptr;
  geometry_msgs::PoseWithCovarianceStampedConstPtr est;
  for (auto it = estimates_.rbegin(); it != estimates_.rend() && !truth; ++it) {
    const auto t = truth_.find(it->first);
    if (t != truth_.end()) {
      truth = &t->second;
      est = it->second;
    }
  }
  ASSERT_TRUE(truth != nullptr) << "no estimate shares a stamp with ground_truth/pose";
  const auto e = conv::toSE2(est->pose.pose), g = conv::toSE2(*truth);
  const double pos = std::hypot(e.x_m - g.x_m, e.y_m - g.y_m);
  double head = std::fabs(std::remainder(e.yaw_rad - g.yaw_rad, 2 * M_PI)) * 180.0 / M_PI;
  std::printf(
      "%s: final estimate (%.3f, %.3f, %.1f deg), truth (%.3f, %.3f, "
      "%.1f deg): position error %.3f m, heading error %.2f deg, %zu estimates\n",
      ros::this_node::getName().c_str(), e.x_m, e.y_m, e.yaw_rad * 180 / M_PI, g.x_m, g.y_m,
      g.yaw_rad * 180 / M_PI, pos, head, estimates_.size());
  EXPECT_LT(pos, max_pos_m_);
  EXPECT_LT(head, max_head_deg_);
  EXPECT_EQ(est->header.frame_id, "map");
  // The covariance is a real one: positive variances in x, y, yaw.
  EXPECT_GT(est->pose.covariance[0], 0.0);
  EXPECT_GT(est->pose.covariance[7], 0.0);
  EXPECT_GT(est->pose.covariance[35], 0.0);
  lock.unlock();
  {
    std::lock_guard<std::mutex> l(mutex_);
    EXPECT_EQ(particles_, 500u);
    EXPECT_EQ(particles_frame_, "map");
    ASSERT_TRUE(model_ != nullptr) << "no rbpf_localizer/color_model received";
    EXPECT_EQ(model_->mode_names.size(), 2u);
    EXPECT_EQ(model_->mean.size(), 3 * model_->color_names.size());
  }
  EXPECT_TRUE(tf_buffer_.canTransform("map", "odom", ros::Time(0), ros::Duration(5.0)))
      << "no map -> odom from the localizer";
  // global_localization (std_srvs/Empty, as amcl) answers.
  ASSERT_TRUE(ros::service::waitForService("global_localization", ros::Duration(5.0)));
  std_srvs::Empty srv;
  EXPECT_TRUE(ros::service::call("global_localization", srv));
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "rbpf_localizer_switching");
  return RUN_ALL_TESTS();
}
