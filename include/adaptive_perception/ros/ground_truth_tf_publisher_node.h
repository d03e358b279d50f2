#pragma once
// ground_truth_tf_publisher: turns the simulator's ground truth into the `map -> odom` transform,
// so that nodes that need the camera pose in `map` (color_estimator with known poses) and rviz can
// run on a simulator bag without a localizer. map -> odom = (map -> base_link)_truth * (odom ->
// base_link)^-1, both at the same stamp (the simulator writes them together).
//
// Its interface (parameters, subscribed and published topics, services, tf) is documented once,
// in docs/nodes/ground_truth_tf_publisher.md; the parameter table there is made from parameters().
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/PoseStamped.h>
#include <message_filters/subscriber.h>
#include <message_filters/sync_policies/exact_time.h>
#include <message_filters/synchronizer.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <deque>
#include <memory>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/ros/node_diagnostics.h"

namespace adaptive_perception {

class GroundTruthTfNode {
 public:
  GroundTruthTfNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Every private parameter the node reads (its doc page's table).
  static std::vector<config::ParameterDoc> parameters();

 private:
  void callback(const geometry_msgs::PoseStampedConstPtr& truth,
                const nav_msgs::OdometryConstPtr& odom);

  using Policy =
      message_filters::sync_policies::ExactTime<geometry_msgs::PoseStamped, nav_msgs::Odometry>;
  std::string map_frame_, odom_frame_, base_frame_;
  int path_length_ = 2000;
  bool publish_tf_ = true;
  message_filters::Subscriber<geometry_msgs::PoseStamped> truth_sub_;
  message_filters::Subscriber<nav_msgs::Odometry> odom_sub_;
  std::unique_ptr<message_filters::Synchronizer<Policy>> sync_;
  tf2_ros::TransformBroadcaster broadcaster_;
  ros::Publisher path_pub_;
  nav_msgs::Path path_;
  ros::Time last_stamp_;
  ros_conv::NodeDiagnostics diagnostics_;  // last: its heartbeat stops before the state it reads goes
};

}  // namespace adaptive_perception
