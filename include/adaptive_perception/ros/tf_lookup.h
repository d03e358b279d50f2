#pragma once
// tf lookups that wait on the WALL clock. tf2_ros::Buffer's own timeout is measured in ros::Time,
// which under use_sim_time stands still when a bag pauses or ends: a callback waiting for a
// transform that never comes would then block its spinner (and every service on that queue) for
// good. These poll the buffer without blocking and give up after a bound in wall seconds.
#include <geometry_msgs/TransformStamped.h>
#include <tf2_ros/buffer.h>

#include <Eigen/Geometry>
#include <string>

namespace adaptive_perception::ros_conv {

/// target <- source at `stamp`, waiting at most `wall_timeout_s` seconds of wall time for it to
/// arrive (0: no wait). Throws tf2::TransformException when it is still missing then.
geometry_msgs::TransformStamped lookupTransformWithin(const tf2_ros::Buffer& buffer,
                                                      const std::string& target_frame,
                                                      const std::string& source_frame,
                                                      const ros::Time& stamp,
                                                      double wall_timeout_s);

struct OdomAndMount {
  Eigen::Isometry3d odom_to_base, base_to_sensor;
};

/// The two transforms a sensor node needs at a measurement's stamp: odometry (odom -> base) and the
/// sensor mount (base -> sensor frame). Waits at most wall_timeout_s of wall time for each; throws
/// tf2::TransformException when either is missing.
OdomAndMount lookupOdomAndMount(const tf2_ros::Buffer& buffer, const std::string& odom_frame,
                                const std::string& base_frame, const std::string& sensor_frame,
                                const ros::Time& stamp, double wall_timeout_s);

}  // namespace adaptive_perception::ros_conv
