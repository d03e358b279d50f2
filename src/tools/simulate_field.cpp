// simulate_field: a legged robot on a RoboCup field (--field; default the four-legged one), seen
// through a camera (--camera, a camera file of config/cameras/; default the AIBO ERS-7's built-in
// camera and head), written to a bag.
//
//   simulate_field --help   (every option with its default, unit and range)
//
// Same arguments give a byte-identical bag. Topics (DESIGN.md): camera/image_raw (yuv422),
// camera/camera_info, camera/labels (mono8 class ids, 255 = background), odom + tf odom ->
// base_link, joint_states + tf of the head chain (tf_static for the fixed links, latched),
// ground_truth/pose (PoseStamped of base_link in map), lighting/state
// (adaptive_perception/LightingState). The bag is written to a temporary file beside FILE.bag and
// renamed when complete; an existing FILE.bag is kept unless --overwrite is given.
#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <rosbag/bag.h>
#include <sensor_msgs/JointState.h>
#include <tf2_msgs/TFMessage.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>

#include "adaptive_perception/LightingState.h"
#include "adaptive_perception/ros/bag_writer.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/sim/field_simulator.h"
#include "adaptive_perception/world/robot_camera.h"
#include "command_line.h"
#include "tick_schedule.h"

using namespace adaptive_perception;
namespace T = adaptive_perception::ros_topics;

namespace {
std::string slash(const char* topic) { return std::string("/") + topic; }
}  // namespace

int main(int argc, char** argv) {
  tools::CommandLine cli(
      "simulate_field",
      "A legged robot on a RoboCup field (default the four-legged one), written to a bag "
      "(deterministic for the seeds).");
  const std::string& output = cli.outputFile("the bag to write", "the bag");
  sim::FieldSimConfig cfg;
  cli.word("script", &cfg.script, sim::lightingScripts(), "the lighting script");
  cli.option("seed", &cfg.seed, "robot route, odometry and image noise");
  cli.option("environment_seed", &cfg.environment_seed, "the venue (0: the nominal lab)");
  cli.fields(sim::FieldSimConfig::fields(), &cfg);
  std::string field = "config/field_4legged.yaml";
  cli.option("field", &field,
             "field description (YAML, docs/fields.md; relative: from the package)");
  double start_time_s = 1.6e9;
  cli.option("start_time_s", &start_time_s, config::closed(1, 4e9), "the bag's first stamp, s");
  std::string camera_file;
  cli.option("camera", &camera_file,
             "camera file (world/robot_camera.h, config/cameras/; relative: from the package; "
             "empty: the AIBO ERS-7's built-in camera); its joint names go into joint_states");
  bool no_compression = false;
  cli.flag("no_compression", &no_compression, "writes the bag uncompressed");
  cli.parse(argc, argv);
  const bool compress = !no_compression;

  try {
    cfg.validate();
    const world::FieldMap map = world::FieldMap::loadYaml(ros_params::resolvePackagePath(field));
    const world::RobotCamera robot =
        camera_file.empty()
            ? world::RobotCamera()
            : world::RobotCamera::loadYaml(ros_params::resolvePackagePath(camera_file));
    const world::PinholeCamera& camera = robot.camera;
    const world::HeadChain& head = robot.head;
    sim::FieldSimulator simulator(map, camera, head, cfg);

    ros_bag::BagWriter bag(output, cli.overwriteGiven(), compress);

    const ros::Time t0(start_time_s);
    // Fixed links of the head chain, latched.
    {
      tf2_msgs::TFMessage tf_static;
      tf_static.transforms.push_back(
          ros_conv::toTransform(head.tiltCamera(), T::kHeadTiltFrame, T::kCameraFrame, t0));
      tf_static.transforms.push_back(ros_conv::toTransform(
          world::HeadChain::cameraOptical(), T::kCameraFrame, T::kCameraOpticalFrame, t0));
      bag.writeLatched("/tf_static", t0, tf_static, "/simulate_field");
    }

    // Event times in integer nanoseconds: odometry ticks and camera ticks, merged.
    const std::set<std::int64_t> odom_ticks = tools::tickTimesNs(cfg.odom_rate_hz, cfg.duration_s);
    const std::set<std::int64_t> camera_ticks =
        tools::tickTimesNs(cfg.camera_rate_hz, cfg.duration_s);
    std::set<std::int64_t> events;
    events = odom_ticks;
    events.insert(camera_ticks.begin(), camera_ticks.end());

    math::SE2 prev_odom = simulator.state().odom_pose;
    double prev_t = 0.0;
    std::uint32_t seq = 0, frames = 0;
    for (const std::int64_t ns : events) {
      const double t = ns * 1e-9;
      simulator.advanceTo(t);
      const sim::SimState& s = simulator.state();
      const ros::Time stamp = t0 + ros::Duration(t);

      tf2_msgs::TFMessage tf;
      tf.transforms.push_back(ros_conv::toTransform(world::planarToIsometry(s.odom_pose),
                                                    T::kOdomFrame, T::kBaseFrame, stamp));
      tf.transforms.push_back(
          ros_conv::toTransform(head.basePan(s.pan_rad), T::kBaseFrame, T::kHeadPanFrame, stamp));
      tf.transforms.push_back(ros_conv::toTransform(head.panTilt(s.tilt_rad), T::kHeadPanFrame,
                                                    T::kHeadTiltFrame, stamp));
      bag.write("/tf", stamp, tf);

      nav_msgs::Odometry odom;
      odom.header.stamp = stamp;
      odom.header.seq = seq;
      odom.header.frame_id = T::kOdomFrame;
      odom.child_frame_id = T::kBaseFrame;
      odom.pose.pose = ros_conv::toPose(s.odom_pose);
      if (t > prev_t) {
        const math::SE2 d = math::between(prev_odom, s.odom_pose);
        odom.twist.twist.linear.x = d.x_m / (t - prev_t);
        odom.twist.twist.linear.y = d.y_m / (t - prev_t);
        odom.twist.twist.angular.z = d.yaw_rad / (t - prev_t);
      }
      // Legged odometry is poor: a loose covariance (x, y in m^2, yaw in rad^2).
      odom.pose.covariance[0] = odom.pose.covariance[7] = 0.01;
      odom.pose.covariance[35] = 0.02;
      odom.pose.covariance[14] = odom.pose.covariance[21] = odom.pose.covariance[28] = 1e6;
      bag.write(slash(T::kOdom), stamp, odom);
      prev_odom = s.odom_pose;
      prev_t = t;

      geometry_msgs::PoseStamped truth;
      truth.header = odom.header;
      truth.header.frame_id = T::kMapFrame;
      truth.pose = ros_conv::toPose(s.true_pose);
      bag.write(slash(T::kGroundTruthPose), stamp, truth);

      sensor_msgs::JointState joints;
      joints.header.stamp = stamp;
      joints.header.seq = seq;
      joints.name = {robot.pan_joint, robot.tilt_joint};
      joints.position = {s.pan_rad, s.tilt_rad};
      bag.write(slash(T::kJointStates), stamp, joints);
      ++seq;

      if (!camera_ticks.count(ns)) continue;
      const sim::CameraImage image = simulator.renderCamera();
      std_msgs::Header h;
      h.stamp = stamp;
      h.seq = frames++;
      h.frame_id = T::kCameraOpticalFrame;
      bag.write(slash(T::kCameraImage), stamp, ros_conv::uyvyToImage(image.uyvy, h));
      bag.write(slash(T::kCameraInfo), stamp, ros_conv::toCameraInfo(camera, h));
      bag.write(slash(T::kCameraLabels), stamp, ros_conv::mono8ToImage(image.labels, h));

      const sim::LightingSnapshot light = simulator.lightingAt(t);
      adaptive_perception::LightingState ls;
      ls.header.stamp = stamp;
      ls.header.seq = h.seq;
      ls.header.frame_id = T::kMapFrame;
      for (const auto& b : light.lighting.banks) {
        ls.bank_names.push_back(b.name);
        ls.bank_on.push_back(b.on);
        ls.bank_intensity.push_back(b.intensity);
        ls.bank_color_temperature_k.push_back(b.color_temperature_k);
      }
      ls.ambient_intensity = light.lighting.ambient_intensity;
      ls.condition = light.condition;
      bag.write(slash(T::kLightingState), stamp, ls);
    }
    const auto bytes = bag.close();
    std::printf(
        "simulate_field: output=%s script=%s seed=%llu environment_seed=%llu frames=%u "
        "duration_s=%.1f bytes=%llu\n",
        output.c_str(), sim::lightingScripts().name(cfg.script).c_str(),
        static_cast<unsigned long long>(cfg.seed),
        static_cast<unsigned long long>(cfg.environment_seed), frames, cfg.duration_s,
        static_cast<unsigned long long>(bytes));
  } catch (const std::exception& e) {
    std::cerr << "simulate_field: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
