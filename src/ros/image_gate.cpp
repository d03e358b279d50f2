#include "adaptive_perception/ros/image_gate.h"

#include <ros/console.h>

#include "adaptive_perception/ros/msg_conversion.h"

namespace adaptive_perception::ros_conv {

ImageGate::Result ImageGate::accept(const sensor_msgs::Image& msg, cv::Mat* bgr,
                                    bool* time_went_back) {
  *time_went_back = !last_stamp_.isZero() && msg.header.stamp < last_stamp_;
  if (*time_went_back) {
    ROS_WARN("%s: image time went backwards (bag looped?): restarting", node_.c_str());
    last_processed_ = ros::Time();
  }
  last_stamp_ = msg.header.stamp;
  if (!last_processed_.isZero() &&
      (msg.header.stamp - last_processed_).toSec() < 1.0 / max_rate_hz_)
    return Result::kTooSoon;
  try {
    *bgr = imageToBgr8(msg);
  } catch (const ImageFormatError& e) {
    ROS_ERROR_THROTTLE(10.0, "%s: image dropped: %s", node_.c_str(), e.what());
    ++bad_images_;
    return Result::kBadImage;
  }
  last_processed_ = msg.header.stamp;
  return Result::kProcess;
}

}  // namespace adaptive_perception::ros_conv
