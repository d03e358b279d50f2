// rostest: line_extractor + ekf_slam_mapper on the simulator loop bag.
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>

#include "adaptive_perception/SaveMap.h"
#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/ros/msg_conversion.h"

namespace ros_conv = adaptive_perception::ros_conv;
namespace math = adaptive_perception::math;

TEST(EkfSlamMapperLoop, ClosesTheLoopAndEndsAtTheTruePose) {
  ros::NodeHandle nh, p("~");
  const int expected = p.param("expected_scans", 1201);
  const double max_err = p.param("max_final_position_error_m", 0.15);
  const double max_yaw = p.param("max_final_yaw_error_rad", 0.05);
  const int min_lm = p.param("min_landmarks", 10), max_lm = p.param("max_landmarks", 60);
  std::mutex mutex;
  std::map<ros::Time, math::SE2> truth;
  geometry_msgs::PoseWithCovarianceStampedConstPtr last_pose;
  visualization_msgs::MarkerArrayConstPtr last_map;
  nav_msgs::PathConstPtr last_path;
  int scans = 0, poses = 0;
  auto a = nh.subscribe<geometry_msgs::PoseWithCovarianceStamped>(
      "ekf_slam_mapper/pose", 2000,
      [&](const geometry_msgs::PoseWithCovarianceStampedConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        last_pose = m;
        ++poses;
      });
  auto b = nh.subscribe<geometry_msgs::PoseStamped>(
      "ground_truth/pose", 5000, [&](const geometry_msgs::PoseStampedConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        truth[m->header.stamp] = ros_conv::toSE2(m->pose);
      });
  auto c = nh.subscribe<sensor_msgs::LaserScan>("scan", 2000,
                                                [&](const sensor_msgs::LaserScanConstPtr&) {
                                                  std::lock_guard<std::mutex> l(mutex);
                                                  ++scans;
                                                });
  auto d = nh.subscribe<visualization_msgs::MarkerArray>(
      "ekf_slam_mapper/map", 5, [&](const visualization_msgs::MarkerArrayConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        last_map = m;
      });
  auto e = nh.subscribe<nav_msgs::Path>("ekf_slam_mapper/path", 5,
                                        [&](const nav_msgs::PathConstPtr& m) {
                                          std::lock_guard<std::mutex> l(mutex);
                                          last_path = m;
                                        });
  tf2_ros::Buffer tf_buffer;
  tf2_ros::TransformListener tf_listener(tf_buffer);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(100.0);
  while (ros::WallTime::now() < deadline) {
    {
      std::lock_guard<std::mutex> l(mutex);
      if (scans >= expected) break;
    }
    ros::WallDuration(0.1).sleep();
  }
  ros::WallDuration(2.0).sleep();
  {
    std::lock_guard<std::mutex> l(mutex);
    ASSERT_EQ(scans, expected);
    EXPECT_GE(poses, expected - 10) << "the mapper kept up with 4x replay";
    ASSERT_TRUE(last_pose);
    EXPECT_EQ(last_pose->header.frame_id, "map");
    const auto it = truth.find(last_pose->header.stamp);
    ASSERT_NE(it, truth.end()) << "ground truth at the last scan's stamp";
    const math::SE2 est = ros_conv::toSE2(last_pose->pose.pose);
    const double err = std::hypot(est.x_m - it->second.x_m, est.y_m - it->second.y_m);
    EXPECT_LT(err, max_err);
    EXPECT_LT(std::fabs(math::angleDiff(est.yaw_rad, it->second.yaw_rad)), max_yaw);
    std::printf("ekf_slam_mapper_loop: final_position_error_m=%.3f\n", err);
    EXPECT_GT(last_pose->pose.covariance[0], 0.0);
    ASSERT_TRUE(last_path);
    EXPECT_GE(static_cast<int>(last_path->poses.size()), expected - 10);
    ASSERT_TRUE(last_map);
    int segments = 0;
    for (const auto& m : last_map->markers)
      if (m.ns == "landmarks") segments = static_cast<int>(m.points.size() / 2);
    EXPECT_GE(segments, min_lm);
  }
  EXPECT_TRUE(tf_buffer.canTransform("map", "odom", ros::Time(0), ros::Duration(1.0)));

  // save_map: writes the map; refuses to overwrite without the flag, leaving the file untouched.
  const std::string path = "/tmp/ekf_slam_mapper_loop_test_map.yaml";
  std::remove(path.c_str());
  ASSERT_TRUE(ros::service::waitForService("ekf_slam_mapper/save_map", 5000));
  adaptive_perception::SaveMap srv;
  srv.request.path = path;
  ASSERT_TRUE(ros::service::call("ekf_slam_mapper/save_map", srv));
  EXPECT_TRUE(srv.response.success) << srv.response.message;
  const YAML::Node y = YAML::LoadFile(path);
  const int n = static_cast<int>(y["landmarks"].size());
  EXPECT_GE(n, min_lm);
  EXPECT_LE(n, max_lm);
  EXPECT_EQ(y["state_covariance"]["dim"].as<int>(), 3 + 2 * n);
  ASSERT_TRUE(ros::service::call("ekf_slam_mapper/save_map", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("exists"), std::string::npos);
  std::remove(path.c_str());
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "ekf_slam_mapper_loop");
  return RUN_ALL_TESTS();
}
