#pragma once
// The tf side of a node that places each measurement by tf at the measurement's stamp
// (color_estimator, rbpf_localizer, ekf_slam_mapper): the node's tf buffer and listener, its
// parameter ~tf_timeout_s (how long, in WALL seconds, to wait for a transform: ros/tf_lookup.h),
// and the count of measurements skipped because a transform was missing, which the node's
// diagnostics report. A lookup that fails returns nothing and warns, naming the node and tf2's
// reason, at most once every 5 s.
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <Eigen/Geometry>
#include <atomic>
#include <mutex>
#include <optional>
#include <string>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/ros/tf_lookup.h"

namespace adaptive_perception::ros_conv {

class MeasurementTf {
 public:
  /// `node` names the node in the warnings. Reads ~tf_timeout_s from `pnh` (default
  /// `default_timeout_s`; throws ros_params::ParamError out of [0, 5]).
  MeasurementTf(std::string node, const ros::NodeHandle& pnh, double default_timeout_s);
  /// The row of ~tf_timeout_s in a node's parameter table; `what`: the transform waited for.
  static config::ParameterDoc parameter(double default_timeout_s, const std::string& what);

  /// target <- source at `stamp`; nothing (counted and warned about) when it does not come in time.
  /// `measurement`: what is skipped ("image", "scan"), for the warning.
  std::optional<Eigen::Isometry3d> transform(const std::string& target, const std::string& source,
                                             const ros::Time& stamp, const char* measurement);
  /// Odometry and the sensor's mount (lookupOdomAndMount); nothing (counted, warned) when either
  /// does not come in time.
  std::optional<OdomAndMount> odomAndMount(const std::string& odom_frame,
                                           const std::string& base_frame,
                                           const std::string& sensor_frame, const ros::Time& stamp,
                                           const char* measurement);

  /// Measurements skipped for want of a transform.
  long skipped() const { return skipped_; }
  const tf2_ros::Buffer& buffer() const { return buffer_; }

 private:
  void missing(const char* measurement, const char* reason);

  std::string node_;
  double timeout_s_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
  std::atomic<long> skipped_{0};
  std::mutex warn_mutex_;
  ros::WallTime last_warning_;
};

}  // namespace adaptive_perception::ros_conv
