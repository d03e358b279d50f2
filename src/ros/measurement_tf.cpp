#include "adaptive_perception/ros/measurement_tf.h"

#include <tf2/exceptions.h>

#include <utility>

#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/params.h"

namespace adaptive_perception::ros_conv {

namespace {
constexpr double kMaxTimeout_s = 5.0, kWarnEvery_s = 5.0;
}  // namespace

MeasurementTf::MeasurementTf(std::string node, const ros::NodeHandle& pnh,
                             double default_timeout_s)
    : node_(std::move(node)),
      timeout_s_(ros_params::getInRange(pnh, "tf_timeout_s", default_timeout_s, 0.0, kMaxTimeout_s)),
      listener_(buffer_) {}

config::ParameterDoc MeasurementTf::parameter(double default_timeout_s, const std::string& what) {
  return {"tf_timeout_s", "double", config::formatReal(default_timeout_s),
          "[0, " + config::formatReal(kMaxTimeout_s) + "]",
          "wall-clock wait for " + what + " at a measurement's stamp before it is skipped (s)"};
}

std::optional<Eigen::Isometry3d> MeasurementTf::transform(const std::string& target,
                                                          const std::string& source,
                                                          const ros::Time& stamp,
                                                          const char* measurement) {
  try {
    return toIsometry(lookupTransformWithin(buffer_, target, source, stamp, timeout_s_).transform);
  } catch (const tf2::TransformException& e) {
    missing(measurement, e.what());
    return std::nullopt;
  }
}

std::optional<OdomAndMount> MeasurementTf::odomAndMount(const std::string& odom_frame,
                                                        const std::string& base_frame,
                                                        const std::string& sensor_frame,
                                                        const ros::Time& stamp,
                                                        const char* measurement) {
  try {
    return lookupOdomAndMount(buffer_, odom_frame, base_frame, sensor_frame, stamp, timeout_s_);
  } catch (const tf2::TransformException& e) {
    missing(measurement, e.what());
    return std::nullopt;
  }
}

void MeasurementTf::missing(const char* measurement, const char* reason) {
  ++skipped_;
  const ros::WallTime now = ros::WallTime::now();
  std::lock_guard<std::mutex> lock(warn_mutex_);
  if (!last_warning_.isZero() && (now - last_warning_).toSec() < kWarnEvery_s) return;
  last_warning_ = now;
  ROS_WARN("%s: no transform for the %s (%s): skipped", node_.c_str(), measurement, reason);
}

}  // namespace adaptive_perception::ros_conv
