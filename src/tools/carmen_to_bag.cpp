// carmen_to_bag: converts a CARMEN log (.clf or .clf.bz2) into a bag.
//
//   carmen_to_bag --help   (every option with its default, unit and range)
//
// Topics: scan (sensor_msgs/LaserScan: angle_min, angle_increment and range_max from the log;
// FLASER and ROBOTLASER1 in `laser`, RLASER in `rear_laser`), odom (nav_msgs/Odometry; --odometry
// auto, the default, takes the lasers' robot poses, so that each scan carries the odometry of its
// own instant, which matters on logs whose ODOM stamps are out of order, like intel; it takes the
// ODOM lines only when the lasers' poses never change; odom_lines and laser_poses force either)
// + tf odom -> base_link, base_link
// -> laser (tf_static when the mounting never changes, else tf at each scan), ground_truth/pose
// (PoseStamped in map) from TRUEPOS. Every stamp is the line's ipc_timestamp, so published relation
// files for these logs line up with the bag. Malformed / truncated / unknown / out-of-order lines
// are reported with their line numbers; out-of-order messages are written in time order. A line
// stamped outside what ros::Time holds (negative, or 2^32 s or more) is skipped and reported with
// its line, and the rest converted. A reading at the laser's maximum range is its "no return" and
// is written as +inf; that range is --max_range_m when given, else the log's PARAM, else the
// no-return value found in the readings, else 81.9 m (io/carmen_log.h). A PARAM maximum range that
// is no range (0, negative, nan) stops the conversion naming its line, unless --max_range_m is
// given. Last line (max_range: each laser's range and where it came from, e.g.
// FLASER:81.83m(inferred)):
//   carmen_to_bag: output=FILE scans=N odom=M truepos=K issues=I out_of_order=O bad_timestamps=B
//   no_returns=R max_range=L
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "adaptive_perception/io/carmen_log.h"
#include "adaptive_perception/ros/bag_writer.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/world/camera_model.h"
#include "command_line.h"
#include "progress.h"

using namespace adaptive_perception;
namespace T = adaptive_perception::ros_topics;

int main(int argc, char** argv) {
  tools::CommandLine cli("carmen_to_bag", "Converts a CARMEN log (.clf or .clf.bz2) into a bag.");
  std::string input;
  cli.option("input", &input, "the CARMEN log")->required();
  const std::string& output = cli.outputFile("the bag to write", "the bag");
  std::string laser_frame = T::kLaserFrame;
  cli.option("laser_frame", &laser_frame, "frame of the front laser's scans");
  long max_issues = 20;
  cli.option("max_issues", &max_issues, config::closed(0, 1e9),
             "malformed lines reported one by one before a summary");
  std::string odometry = "auto";
  cli.option("odometry", &odometry,
             "odometry source: the lasers' robot poses unless they never change (auto), or "
             "either forced")
      ->oneOf({"auto", "odom_lines", "laser_poses"});
  // The reader's default timestamp range, [0, 2^32 - 1] s, is what ros::Time holds: a line stamped
  // outside it is skipped and reported by the reader, where ros::Time would throw and stop the
  // conversion.
  io::CarmenReadOptions read_options;
  cli.option("max_range_m", &read_options.max_range_m, config::closed(0, 1000),
             "every laser's maximum range (its no-return value), m, over the log's PARAM, "
             "ROBOTLASER1 field and the value found in the readings; 0: from the log");
  long max_decompressed_mib = static_cast<long>(read_options.max_decompressed_bytes >> 20);
  cli.option("max_decompressed_mib", &max_decompressed_mib, config::closed(1, 1 << 20),
             "a .bz2 log that decompresses to more is refused, MiB");
  cli.parse(argc, argv);
  read_options.max_decompressed_bytes = static_cast<std::uint64_t>(max_decompressed_mib) << 20;
  try {
    io::CarmenLog log = io::readCarmenLog(input, read_options);
    log.sortByTime();
    for (long i = 0; i < static_cast<long>(log.issues.size()) && i < max_issues; ++i)
      std::fprintf(stderr, "%s:%ld: %s\n", input.c_str(), log.issues[i].line,
                   log.issues[i].what.c_str());
    if (static_cast<long>(log.issues.size()) > max_issues)
      std::fprintf(stderr, "%s: ... %zu more issues\n", input.c_str(),
                   log.issues.size() - max_issues);
    if (log.bad_timestamps > 0)
      std::fprintf(stderr,
                   "%s: warning: %ld lines skipped for a timestamp outside [%.0f, %.0f] s, the "
                   "range of ros::Time (listed above, up to --max_issues)\n",
                   input.c_str(), log.bad_timestamps, read_options.min_timestamp_s,
                   read_options.max_timestamp_s);
    if (log.lasers.empty()) throw std::runtime_error(input + ": no laser messages");

    ros_bag::BagWriter bag(output, cli.overwriteGiven());
    auto stamp = [](double t) { return ros::Time(std::max(t, 1e-6)); };

    // Laser mounting: constant across the log -> tf_static.
    const math::SE2 mount0 =
        math::between(log.lasers.front().robot_pose, log.lasers.front().laser_pose);
    bool constant_mount = true;
    for (const auto& l : log.lasers) {
      const math::SE2 m = math::between(l.robot_pose, l.laser_pose);
      if (std::hypot(m.x_m - mount0.x_m, m.y_m - mount0.y_m) > 1e-3 ||
          std::fabs(m.yaw_rad - mount0.yaw_rad) > 1e-3) {
        constant_mount = false;
        break;
      }
    }
    if (constant_mount) {
      tf2_msgs::TFMessage st;
      const ros::Time t0 = stamp(log.lasers.front().timestamp_s);
      st.transforms.push_back(
          ros_conv::toTransform(world::planarToIsometry(mount0), T::kBaseFrame, laser_frame, t0));
      bag.writeLatched("/tf_static", t0, st, "/carmen_to_bag");
    }
    std::uint32_t seq = 0;
    tools::Progress progress("carmen_to_bag", static_cast<long>(log.lasers.size()), "scans");
    for (const auto& l : log.lasers) {
      progress.update(static_cast<long>(seq) + 1);
      sensor_msgs::LaserScan s;
      s.header.stamp = stamp(l.timestamp_s);
      s.header.seq = seq++;
      s.header.frame_id = l.type == "RLASER" ? "rear_laser" : laser_frame;
      s.angle_min = static_cast<float>(l.angle_min_rad);
      s.angle_increment = static_cast<float>(l.angle_increment_rad);
      s.angle_max =
          static_cast<float>(l.angle_min_rad + (l.ranges_m.size() - 1) * l.angle_increment_rad);
      s.range_min = 0.01f;
      s.range_max = static_cast<float>(l.max_range_m);
      s.ranges = l.ranges_m;
      bag.write("/" + std::string(T::kScan), s.header.stamp, s);
      if (!constant_mount) {
        tf2_msgs::TFMessage tf;
        tf.transforms.push_back(ros_conv::toTransform(
            world::planarToIsometry(math::between(l.robot_pose, l.laser_pose)), T::kBaseFrame,
            s.header.frame_id, s.header.stamp));
        bag.write("/tf", s.header.stamp, tf);
      }
    }
    auto writeOdom = [&](double t, const math::SE2& pose, double tv, double rv) {
      nav_msgs::Odometry o;
      o.header.stamp = stamp(t);
      o.header.frame_id = T::kOdomFrame;
      o.child_frame_id = T::kBaseFrame;
      o.pose.pose = ros_conv::toPose(pose);
      o.twist.twist.linear.x = tv;
      o.twist.twist.angular.z = rv;
      bag.write("/" + std::string(T::kOdom), o.header.stamp, o);
      tf2_msgs::TFMessage tf;
      tf.transforms.push_back(ros_conv::toTransform(world::planarToIsometry(pose), T::kOdomFrame,
                                                    T::kBaseFrame, o.header.stamp));
      bag.write("/tf", o.header.stamp, tf);
    };
    if (odometry == "odom_lines" && log.odometry.empty())
      throw std::runtime_error(input + ": --odometry odom_lines, but the log has no ODOM lines");
    // auto: the lasers' own robot poses, so that each scan carries the odometry of its own instant
    // (intel's ODOM stamps are out of order against its FLASER lines), unless those poses never
    // change (a logger that left them zero) and the log has ODOM lines.
    const bool from_lines =
        odometry == "odom_lines" ||
        (odometry == "auto" && !log.odometry.empty() && !io::laserPosesMove(log));
    if (from_lines) {
      for (const auto& o : log.odometry) writeOdom(o.timestamp_s, o.pose, o.tv_mps, o.rv_radps);
    } else {
      for (const auto& l : log.lasers) writeOdom(l.timestamp_s, l.robot_pose, 0.0, 0.0);
    }
    for (const auto& t : log.true_poses) {
      geometry_msgs::PoseStamped p;
      p.header.stamp = stamp(t.timestamp_s);
      p.header.frame_id = T::kMapFrame;
      p.pose = ros_conv::toPose(t.true_pose);
      bag.write("/" + std::string(T::kGroundTruthPose), p.header.stamp, p);
    }
    bag.close();
    std::printf(
        "carmen_to_bag: output=%s scans=%zu odom=%zu truepos=%zu issues=%zu out_of_order=%ld "
        "bad_timestamps=%ld no_returns=%ld max_range=%s\n",
        output.c_str(), log.lasers.size(), from_lines ? log.odometry.size() : log.lasers.size(),
        log.true_poses.size(), log.issues.size(), log.out_of_order, log.bad_timestamps,
        log.no_returns, io::maxRangeSummary(log).c_str());
  } catch (const std::exception& e) {
    std::cerr << "carmen_to_bag: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
