// rostest: line_extractor + ekf_slam_mapper on the simulator loop bag.
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <nav_msgs/GetMap.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "adaptive_perception/SaveMap.h"
#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/slam/occupancy_grid.h"
#include "rostest_support.h"

namespace ros_conv = adaptive_perception::ros_conv;
namespace math = adaptive_perception::math;
namespace rostest_support = adaptive_perception::rostest_support;

TEST(EkfSlamMapperLoop, ClosesTheLoopAndEndsAtTheTruePose) {
  ros::NodeHandle nh, p("~");
  const int expected = p.param("expected_scans", 1201);
  const double max_err = p.param("max_final_position_error_m", 0.15);
  const double max_yaw = p.param("max_final_yaw_error_rad", 0.05);
  const int min_lm = p.param("min_landmarks", 10), max_lm = p.param("max_landmarks", 60);
  rostest_support::TopicRecord<geometry_msgs::PoseWithCovarianceStamped> poses(
      nh, "ekf_slam_mapper/pose", 2000);
  rostest_support::TopicRecord<geometry_msgs::PoseStamped> truth_poses(nh, "ground_truth/pose",
                                                                        5000, true);
  rostest_support::TopicRecord<sensor_msgs::LaserScan> scans(nh, "scan", 2000);
  rostest_support::TopicRecord<visualization_msgs::MarkerArray> map(nh, "ekf_slam_mapper/map", 5);
  rostest_support::TopicRecord<nav_msgs::Path> path_record(nh, "ekf_slam_mapper/path", 5);
  rostest_support::TopicRecord<nav_msgs::OccupancyGrid> grids(nh, "map", 5);
  tf2_ros::Buffer tf_buffer;
  tf2_ros::TransformListener tf_listener(tf_buffer);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  rostest_support::waitUntil([&] { return scans.count() >= expected; }, 100.0, 0.1);
  ros::WallDuration(2.0).sleep();
  std::map<ros::Time, math::SE2> truth;
  for (const auto& m : truth_poses.all()) truth[m->header.stamp] = ros_conv::toSE2(m->pose);
  {
    ASSERT_EQ(scans.count(), expected);
    EXPECT_GE(poses.count(), expected - 10) << "the mapper answered the scans";
    const auto last_pose = poses.last();
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
    const auto last_path = path_record.last();
    ASSERT_TRUE(last_path);
    EXPECT_GE(static_cast<int>(last_path->poses.size()), expected - 10);
    const auto last_map = map.last();
    ASSERT_TRUE(last_map);
    int segments = 0;
    for (const auto& m : last_map->markers)
      if (m.ns == "landmarks") segments = static_cast<int>(m.points.size() / 2);
    EXPECT_GE(segments, min_lm);
  }
  EXPECT_TRUE(tf_buffer.canTransform("map", "odom", ros::Time(0), ros::Duration(1.0)));

  // The occupancy grid: published on map while the bag plays; the robot's true path lies on free
  // cells, the walls' hits make occupied ones, and dynamic_map serves the same grid.
  ros::WallDuration(3.0).sleep();  // the last render after the bag's end (map_update_interval_s 2)
  {
    const auto last_grid = grids.last();
    ASSERT_TRUE(last_grid) << "no occupancy grid on map";
    EXPECT_GE(grids.count(), 3);
    EXPECT_EQ(last_grid->header.frame_id, "map");
    EXPECT_FLOAT_EQ(last_grid->info.resolution, 0.05f);
    ASSERT_EQ(last_grid->data.size(),
              static_cast<size_t>(last_grid->info.width) * last_grid->info.height);
    long occupied = 0, free_cells = 0;
    for (std::int8_t v : last_grid->data) {
      occupied += v == 100;
      free_cells += v == 0;
    }
    EXPECT_GT(occupied, 500) << "the corridor's walls";
    EXPECT_GT(free_cells, occupied);
    long on_path = 0, path_free = 0;
    const double res = last_grid->info.resolution;
    for (const auto& [t, g] : truth) {
      const long cx =
          static_cast<long>(std::floor((g.x_m - last_grid->info.origin.position.x) / res));
      const long cy =
          static_cast<long>(std::floor((g.y_m - last_grid->info.origin.position.y) / res));
      if (cx < 0 || cy < 0 || cx >= last_grid->info.width || cy >= last_grid->info.height) continue;
      ++on_path;
      path_free += last_grid->data[cy * last_grid->info.width + cx] == 0;
    }
    EXPECT_GT(on_path, 1000);
    EXPECT_GE(path_free, 0.95 * on_path) << "the true path crosses free cells";
  }
  nav_msgs::GetMap get;
  ASSERT_TRUE(ros::service::waitForService("dynamic_map", 5000));
  ASSERT_TRUE(ros::service::call("dynamic_map", get));
  EXPECT_GT(get.response.map.info.width, 100u);
  EXPECT_EQ(get.response.map.data.size(),
            static_cast<size_t>(get.response.map.info.width) * get.response.map.info.height);

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
  // The grid beside it, in map_server's format, read back by the project's reader.
  const std::string grid_yaml = "/tmp/ekf_slam_mapper_loop_test_map_grid.yaml";
  const std::string grid_pgm = "/tmp/ekf_slam_mapper_loop_test_map_grid.pgm";
  const adaptive_perception::slam::OccupancyGrid saved =
      adaptive_perception::slam::readMapServerFiles(grid_yaml);
  EXPECT_EQ(saved.width, static_cast<int>(get.response.map.info.width));
  EXPECT_EQ(saved.height, static_cast<int>(get.response.map.info.height));
  EXPECT_NEAR(saved.origin_x_m, get.response.map.info.origin.position.x, 1e-6);
  ASSERT_TRUE(ros::service::call("ekf_slam_mapper/save_map", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find("exists"), std::string::npos);
  // Only the grid left from before: still refused, naming it.
  std::remove(path.c_str());
  ASSERT_TRUE(ros::service::call("ekf_slam_mapper/save_map", srv));
  EXPECT_FALSE(srv.response.success);
  EXPECT_NE(srv.response.message.find(grid_yaml), std::string::npos) << srv.response.message;
  for (const std::string& f : {path, grid_yaml, grid_pgm}) std::remove(f.c_str());

  // ~reset forgets the map: the reply says what went, and there is no grid to serve until scans
  // come again.
  std_srvs::Trigger reset;
  ASSERT_TRUE(ros::service::call("ekf_slam_mapper/reset", reset));
  EXPECT_TRUE(reset.response.success);
  EXPECT_NE(reset.response.message.find("landmarks"), std::string::npos) << reset.response.message;
  nav_msgs::GetMap after;
  EXPECT_FALSE(ros::service::call("dynamic_map", after));
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "ekf_slam_mapper_loop");
  return RUN_ALL_TESTS();
}
