// rostest: appearance_localizer on a simulated run of the indoor building, scored against the
// true pose and place.
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

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "appearance_localizer_sim");
  return RUN_ALL_TESTS();
}
