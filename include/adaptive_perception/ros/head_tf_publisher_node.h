#pragma once
// head_tf_publisher: a robot's head chain from a camera file (world/robot_camera.h,
// config/cameras/), so that a bag or a robot with joint_states but no URDF gives the nodes the
// camera's pose: for each joint_states message that holds the file's pan and tilt joints (a NAO's
// HeadYaw and HeadPitch), base_link -> head_pan_link (pan about z) and head_pan_link ->
// head_tilt_link (tilt about y) at the message's stamp; once, latched on tf_static, head_tilt_link
// -> camera_link (the lens's offset and pitch) and camera_link -> camera_optical_frame.
//
// When the camera file has a torso_pitch_reference_rad and ~lean_from_imu is on, the torso's
// pitch from `imu` (the reading stamped nearest the joint_states' stamp, if within
// ~torso_pitch_max_age_s of it) leans the head about base_link's y axis by its difference from the
// reference (HeadChain::leanRad(); the body's lean, which the head's joints do not see); with no
// reading near, no lean.
//
// A message without either joint, with a non-finite angle or one outside the file's joint range,
// or with more positions than names is skipped with a throttled error naming what was wrong, as is
// an imu message whose orientation is not finite, zero or marked as not given (covariance[0] -1);
// the node keeps running. Its interface is documented once, in docs/nodes/head_tf_publisher.md;
// the parameter table there is made from parameters().
#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/ros/node_diagnostics.h"
#include "adaptive_perception/world/robot_camera.h"

namespace adaptive_perception {

class HeadTfNode {
 public:
  HeadTfNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Every private parameter the node reads (its doc page's table).
  static std::vector<config::ParameterDoc> parameters();

 private:
  void callback(const sensor_msgs::JointStateConstPtr& msg);
  void imuCallback(const sensor_msgs::ImuConstPtr& msg);
  void check(diagnostic_updater::DiagnosticStatusWrapper& stat);

  world::RobotCamera camera_;
  std::string camera_file_;
  std::string base_frame_, pan_frame_, tilt_frame_, camera_frame_, optical_frame_;
  bool lean_from_imu_ = false;  // ~lean_from_imu and a reference in the camera file
  double torso_pitch_max_age_s_ = 0.0;
  std::deque<std::pair<ros::Time, double>> torso_pitch_;  // imu readings of the last seconds
  long published_ = 0, skipped_ = 0, leaned_ = 0, imu_skipped_ = 0;
  std::string last_problem_, last_imu_problem_;
  ros::Subscriber sub_, imu_sub_;
  tf2_ros::TransformBroadcaster broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  ros_conv::NodeDiagnostics
      diagnostics_;  // last: its heartbeat stops before the state it reads goes
};

}  // namespace adaptive_perception
