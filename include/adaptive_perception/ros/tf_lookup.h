#pragma once
// The two transforms a sensor node needs at a measurement's stamp: odometry (odom -> base) and the
// sensor mount (base -> sensor frame).
#include <tf2_ros/buffer.h>

#include <Eigen/Geometry>
#include <string>

namespace adaptive_perception::ros_conv {

struct OdomAndMount {
  Eigen::Isometry3d odom_to_base, base_to_sensor;
};

/// Waits up to timeout_s for both; throws tf2::TransformException when either is missing.
OdomAndMount lookupOdomAndMount(const tf2_ros::Buffer& buffer, const std::string& odom_frame,
                                const std::string& base_frame, const std::string& sensor_frame,
                                const ros::Time& stamp, double timeout_s);

}  // namespace adaptive_perception::ros_conv
