#include "adaptive_perception/ros/tf_lookup.h"

#include <tf2/buffer_core.h>

#include "adaptive_perception/ros/msg_conversion.h"

namespace adaptive_perception::ros_conv {

geometry_msgs::TransformStamped lookupTransformWithin(const tf2_ros::Buffer& buffer,
                                                      const std::string& target_frame,
                                                      const std::string& source_frame,
                                                      const ros::Time& stamp,
                                                      double wall_timeout_s) {
  // BufferCore's calls never wait (tf2_ros::Buffer's overloads with a timeout sleep in ros::Time).
  const tf2::BufferCore& core = buffer;
  // A frame id tf2 refuses outright gets its exception at once (polling would print tf2's
  // warning every 2 ms).
  for (const std::string* f : {&target_frame, &source_frame})
    if (f->empty() || (*f)[0] == '/')
      return core.lookupTransform(target_frame, source_frame, stamp);
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(wall_timeout_s);
  while (!core.canTransform(target_frame, source_frame, stamp) && ros::ok() &&
         ros::WallTime::now() < deadline)
    ros::WallDuration(0.002).sleep();
  return core.lookupTransform(target_frame, source_frame, stamp);  // throws with tf2's reason
}

OdomAndMount lookupOdomAndMount(const tf2_ros::Buffer& buffer, const std::string& odom_frame,
                                const std::string& base_frame, const std::string& sensor_frame,
                                const ros::Time& stamp, double wall_timeout_s) {
  OdomAndMount out;
  out.odom_to_base = toIsometry(
      lookupTransformWithin(buffer, odom_frame, base_frame, stamp, wall_timeout_s).transform);
  out.base_to_sensor = toIsometry(
      lookupTransformWithin(buffer, base_frame, sensor_frame, stamp, wall_timeout_s).transform);
  return out;
}

}  // namespace adaptive_perception::ros_conv
