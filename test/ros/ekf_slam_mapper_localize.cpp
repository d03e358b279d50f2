// rostest: ekf_slam_mapper with ~initial_map localizes along the simulator loop bag against the
// bag's saved line map, and does not extend it.
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "rostest_support.h"

namespace ros_conv = adaptive_perception::ros_conv;
namespace math = adaptive_perception::math;
namespace rostest_support = adaptive_perception::rostest_support;

TEST(EkfSlamMapperLocalize, StaysOnTheTruePathAgainstTheLoadedMapWithoutExtendingIt) {
  ros::NodeHandle nh, p("~");
  const int expected = p.param("expected_scans", 1201);
  const double max_err = p.param("max_position_error_m", 0.2);
  const double max_final = p.param("max_final_position_error_m", 0.1);
  const int min_segments = p.param("min_map_segments", 10);
  rostest_support::TopicRecord<geometry_msgs::PoseWithCovarianceStamped> poses(
      nh, "ekf_slam_mapper/pose", 2000, true);
  rostest_support::TopicRecord<geometry_msgs::PoseStamped> truth_poses(nh, "ground_truth/pose",
                                                                        5000, true);
  rostest_support::TopicRecord<sensor_msgs::LaserScan> scans(nh, "scan", 2000);
  rostest_support::TopicRecord<visualization_msgs::MarkerArray> map(nh, "ekf_slam_mapper/map", 5);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  rostest_support::waitUntil([&] { return scans.count() >= expected; }, 100.0, 0.1);
  ros::WallDuration(2.0).sleep();
  ASSERT_EQ(scans.count(), expected);
  ASSERT_GE(poses.count(), expected - 10) << "the mapper answered the scans";
  std::map<ros::Time, math::SE2> truth;
  for (const auto& m : truth_poses.all()) truth[m->header.stamp] = ros_conv::toSE2(m->pose);
  double worst = 0.0, final_err = -1.0;
  int compared = 0;
  for (const auto& m : poses.all()) {
    const auto it = truth.find(m->header.stamp);
    if (it == truth.end()) continue;
    const math::SE2 est = ros_conv::toSE2(m->pose.pose);
    final_err = std::hypot(est.x_m - it->second.x_m, est.y_m - it->second.y_m);
    worst = std::max(worst, final_err);
    ++compared;
  }
  std::printf("ekf_slam_mapper_localize: %d poses, worst_position_error_m=%.3f "
              "final_position_error_m=%.3f\n",
              compared, worst, final_err);
  EXPECT_GE(compared, expected - 10);
  EXPECT_LT(worst, max_err);
  EXPECT_LT(final_err, max_final);
  const auto last_map = map.last();
  ASSERT_TRUE(last_map);
  int fixed = 0, in_state = 0, tentative = 0;
  for (const auto& m : last_map->markers) {
    if (m.action != visualization_msgs::Marker::ADD) continue;
    const int n = static_cast<int>(m.points.size() / 2);
    if (m.ns == "fixed landmarks") fixed = n;
    if (m.ns == "landmarks") in_state = n;
    if (m.ns == "tentative landmarks") tentative = n;
  }
  EXPECT_GE(fixed, min_segments) << "the loaded map's walls";
  EXPECT_EQ(in_state, 0) << "the map was extended";
  EXPECT_EQ(tentative, 0) << "the map was extended";
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "ekf_slam_mapper_localize");
  return RUN_ALL_TESTS();
}
