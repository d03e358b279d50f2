// rostest: appearance_localizer on a simulated run of the indoor building, scored against the
// true pose and place.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>

#include "adaptive_perception/PlaceRecognition.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "rostest_support.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/sim/indoor_world.h"

namespace ap = adaptive_perception;

TEST(AppearanceLocalizerSim, ClassifiesRoomsAndLocalizes) {
  ros::NodeHandle nh, p("~");
  const double min_classified = p.param("min_classified_fraction", 0.5);
  const double min_accuracy = p.param("min_classified_accuracy", 0.85);
  const double max_median_err = p.param("max_median_position_error_m", 1.5);
  const ap::sim::IndoorWorld world = ap::sim::IndoorWorld::loadYaml(
      ap::ros_params::resolvePackagePath("config/worlds/indoor_building.yaml"));
  std::mutex mutex;
  std::map<ros::Time, ap::math::SE2> truth;
  std::vector<ap::PlaceRecognition> rooms;
  std::map<ros::Time, ap::math::SE2> estimates;
  const ap::rostest_support::PhaseListener player(nh);
  auto b = nh.subscribe<geometry_msgs::PoseStamped>(
      "ground_truth/pose", 10000, [&](const geometry_msgs::PoseStampedConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        truth[m->header.stamp] = ap::ros_conv::toSE2(m->pose);
      });
  auto c = nh.subscribe<ap::PlaceRecognition>("appearance_localizer/room", 1000,
                                              [&](const ap::PlaceRecognitionConstPtr& m) {
                                                std::lock_guard<std::mutex> l(mutex);
                                                rooms.push_back(*m);
                                              });
  auto d = nh.subscribe<geometry_msgs::PoseWithCovarianceStamped>(
      "appearance_localizer/pose", 1000,
      [&](const geometry_msgs::PoseWithCovarianceStampedConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        estimates[m->header.stamp] = ap::ros_conv::toSE2(m->pose.pose);
      });
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ASSERT_TRUE(player.waitFor("done", 280.0)) << "the player did not finish";
  std::lock_guard<std::mutex> l(mutex);
  ASSERT_GE(rooms.size(), 200u);
  int scored = 0, classified = 0, right = 0, wrong = 0;
  std::vector<double> errors;
  for (const auto& r : rooms) {
    const auto t = truth.find(r.header.stamp);
    if (t == truth.end()) continue;
    const int place = world.placeAt({t->second.x_m, t->second.y_m});
    if (place < 0) continue;
    ++scored;
    if (r.place == "not classified" || r.place == "unknown") continue;
    ++classified;
    (r.place == world.places[place].name ? right : wrong) += 1;
    const auto e = estimates.find(r.header.stamp);
    if (e != estimates.end())
      errors.push_back(std::hypot(e->second.x_m - t->second.x_m, e->second.y_m - t->second.y_m));
  }
  ASSERT_GT(scored, 200);
  ASSERT_GT(classified, 0);
  std::sort(errors.begin(), errors.end());
  const double median = errors.empty() ? 1e9 : errors[errors.size() / 2];
  std::printf(
      "appearance_localizer_sim: scored=%d classified=%d right=%d wrong=%d score=%.1f "
      "median_position_error_m=%.2f\n",
      scored, classified, right, wrong, right - 0.5 * wrong, median);
  EXPECT_GE(static_cast<double>(classified) / scored, min_classified);
  EXPECT_GE(static_cast<double>(right) / classified, min_accuracy);
  EXPECT_LE(median, max_median_err);
}

// After the run (the node still up): an initial pose in another frame and one with a covariance
// that is not positive definite are refused, a good one is taken; the node's diagnostics count
// what it took.
TEST(AppearanceLocalizerSim, TakesAnInitialPoseOnlyInTheMapFrameWithAValidCovariance) {
  ros::NodeHandle nh;
  std::mutex mutex;
  std::string taken;
  auto diag = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArrayConstPtr& m) {
        for (const auto& s : m->status)
          if (s.name.find("appearance_localizer") != std::string::npos)
            for (const auto& kv : s.values)
              if (kv.key == "initial poses taken") {
                std::lock_guard<std::mutex> l(mutex);
                taken = kv.value;
              }
      });
  ros::Publisher pub = nh.advertise<geometry_msgs::PoseWithCovarianceStamped>("initialpose", 3);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  for (int i = 0; i < 100 && pub.getNumSubscribers() == 0; ++i) ros::WallDuration(0.1).sleep();
  ASSERT_GT(pub.getNumSubscribers(), 0u) << "appearance_localizer does not subscribe initialpose";
  geometry_msgs::PoseWithCovarianceStamped m;
  m.pose.pose.position.x = 2.0;
  m.pose.pose.orientation.w = 1.0;
  m.pose.covariance[0] = m.pose.covariance[7] = 0.25;
  m.pose.covariance[35] = 0.07;
  m.header.frame_id = "odom";  // not the map frame: refused
  pub.publish(m);
  geometry_msgs::PoseWithCovarianceStamped bad = m;
  bad.header.frame_id = "map";
  bad.pose.covariance[7] = -1.0;  // not positive definite: refused
  pub.publish(bad);
  m.header.frame_id = "map";
  pub.publish(m);
  std::string last;
  for (int i = 0; i < 150; ++i) {  // the diagnostics heartbeat reports about once a second
    {
      std::lock_guard<std::mutex> l(mutex);
      last = taken;
    }
    if (last == "1") break;
    ros::WallDuration(0.1).sleep();
  }
  ros::WallDuration(2.5).sleep();  // two more reports: the count stays at one
  std::lock_guard<std::mutex> l(mutex);
  EXPECT_EQ(last, "1");
  EXPECT_EQ(taken, "1");
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "appearance_localizer_sim");
  return RUN_ALL_TESTS();
}
