// simulate_laser: a robot with a 2-D laser driving a route through a polygon world, written to a
// bag.
//
//   simulate_laser --help   (every option with its default, unit and range)
//
// Topics: scan (LaserScan in `laser`), odom + tf odom -> base_link, tf_static base_link -> laser,
// ground_truth/pose (PoseStamped in map), ground_truth/walls (adaptive_perception/LineSegmentArray
// in `laser` at each scan's stamp: the part of every wall the scan hit, num_points = returns on
// it). Deterministic for a seed. Last line: `simulate_laser: output=FILE scans=N duration_s=S`.
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>

#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/ros/bag_writer.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/sim/laser_simulator.h"
#include "adaptive_perception/world/camera_model.h"
#include "command_line.h"
#include "tick_schedule.h"

using namespace adaptive_perception;
namespace T = adaptive_perception::ros_topics;

int main(int argc, char** argv) {
  tools::CommandLine cli("simulate_laser",
                         "A robot with a 2-D laser driving a route through a polygon world, "
                         "written to a bag (deterministic for a seed).");
  std::string world_path = "config/worlds/office.yaml";
  cli.option("world", &world_path, "the world (YAML; relative paths from the package)");
  const std::string& output = cli.outputFile("the bag to write", "the bag");
  double duration = 60.0;
  cli.option("duration_s", &duration, config::Range{0, 36000, true, false}, "simulated time, s");
  const std::uint64_t& seed = cli.seed();
  double odom_rate = 20.0;
  cli.option("odom_rate_hz", &odom_rate, config::closed(1, 1000), "odometry rate, Hz");
  cli.parse(argc, argv);
  try {
    const sim::LaserWorld world =
        sim::LaserWorld::loadYaml(ros_params::resolvePackagePath(world_path));
    sim::LaserSimulator simulator(world, seed);
    ros_bag::BagWriter bag(output, cli.overwriteGiven());
    const ros::Time t0(1.6e9);
    {
      tf2_msgs::TFMessage st;
      st.transforms.push_back(ros_conv::toTransform(world::planarToIsometry(world.laser.mount),
                                                    T::kBaseFrame, T::kLaserFrame, t0));
      bag.writeLatched("/tf_static", t0, st, "/simulate_laser");
    }
    const std::set<std::int64_t> odom_ticks = tools::tickTimesNs(odom_rate, duration);
    const std::set<std::int64_t> scan_ticks = tools::tickTimesNs(world.laser.rate_hz, duration);
    std::set<std::int64_t> events = odom_ticks;
    events.insert(scan_ticks.begin(), scan_ticks.end());
    double t_prev = 0.0;
    long scans = 0;
    for (std::int64_t ns : events) {
      const double t = ns * 1e-9;
      simulator.step(t - t_prev);
      t_prev = t;
      const ros::Time stamp = t0 + ros::Duration(t);
      nav_msgs::Odometry o;
      o.header.stamp = stamp;
      o.header.frame_id = T::kOdomFrame;
      o.child_frame_id = T::kBaseFrame;
      o.pose.pose = ros_conv::toPose(simulator.odomPose());
      bag.write("/" + std::string(T::kOdom), stamp, o);
      tf2_msgs::TFMessage tf;
      tf.transforms.push_back(ros_conv::toTransform(world::planarToIsometry(simulator.odomPose()),
                                                    T::kOdomFrame, T::kBaseFrame, stamp));
      bag.write("/tf", stamp, tf);
      geometry_msgs::PoseStamped truth;
      truth.header.stamp = stamp;
      truth.header.frame_id = T::kMapFrame;
      truth.pose = ros_conv::toPose(simulator.truePose());
      bag.write("/" + std::string(T::kGroundTruthPose), stamp, truth);
      if (!scan_ticks.count(ns)) continue;
      std::vector<sim::VisibleWall> visible;
      const laser::LaserScan2D s = simulator.scan(&visible);
      sensor_msgs::LaserScan msg;
      msg.header.stamp = stamp;
      msg.header.seq = static_cast<std::uint32_t>(scans++);
      msg.header.frame_id = T::kLaserFrame;
      msg.angle_min = static_cast<float>(s.angle_min_rad);
      msg.angle_increment = static_cast<float>(s.angle_increment_rad);
      msg.angle_max = static_cast<float>(s.bearing(static_cast<int>(s.ranges_m.size()) - 1));
      msg.range_min = static_cast<float>(s.range_min_m);
      msg.range_max = static_cast<float>(s.range_max_m);
      msg.scan_time = static_cast<float>(1.0 / world.laser.rate_hz);
      msg.ranges = s.ranges_m;
      bag.write("/" + std::string(T::kScan), stamp, msg);
      std::vector<laser::LineSegment> seen;
      for (const auto& v : visible) {
        laser::LineSegment w;
        const Eigen::Vector2d d = v.end_m - v.start_m;
        Eigen::Vector2d n(-d.y(), d.x());
        if (n.norm() > 0) n.normalize();
        if (n.dot(v.start_m) < 0) n = -n;
        w.line.rho_m = n.dot(v.start_m);
        w.line.alpha_rad = std::atan2(n.y(), n.x());
        w.start_m = v.start_m;
        w.end_m = v.end_m;
        w.num_points = v.hits;
        seen.push_back(w);
      }
      const LineSegmentArray walls = ros_conv::toLineSegmentArray(seen, msg.header);
      bag.write("/ground_truth/walls", stamp, walls);
    }
    bag.close();
    std::printf("simulate_laser: output=%s world=%s scans=%ld duration_s=%.1f\n", output.c_str(),
                world.name.c_str(), scans, duration);
  } catch (const std::exception& e) {
    std::cerr << "simulate_laser: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
