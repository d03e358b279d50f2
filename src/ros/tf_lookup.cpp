#include "adaptive_perception/ros/tf_lookup.h"

#include "adaptive_perception/ros/msg_conversion.h"

namespace adaptive_perception::ros_conv {

OdomAndMount lookupOdomAndMount(const tf2_ros::Buffer& buffer, const std::string& odom_frame,
                                const std::string& base_frame, const std::string& sensor_frame,
                                const ros::Time& stamp, double timeout_s) {
  OdomAndMount out;
  out.odom_to_base = toIsometry(
      buffer.lookupTransform(odom_frame, base_frame, stamp, ros::Duration(timeout_s)).transform);
  out.base_to_sensor = toIsometry(
      buffer.lookupTransform(base_frame, sensor_frame, stamp, ros::Duration(timeout_s)).transform);
  return out;
}

}  // namespace adaptive_perception::ros_conv
