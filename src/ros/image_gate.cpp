#include "adaptive_perception/ros/image_gate.h"

#include <ros/console.h>

#include "adaptive_perception/ros/msg_conversion.h"

namespace adaptive_perception::ros_conv {

ImageGate::Result ImageGate::accept(const sensor_msgs::Image& msg, cv::Mat* image,
                                    bool* time_went_back) {
  const StampOrder::Verdict order = order_.check(msg.header.stamp, "");
  *time_went_back = order == StampOrder::Verdict::kRestart;
  if (order == StampOrder::Verdict::kDrop) return Result::kOutOfOrder;
  if (*time_went_back) last_processed_ = ros::Time();
  if (max_rate_hz_ > 0.0 && !last_processed_.isZero() &&
      (msg.header.stamp - last_processed_).toSec() < 1.0 / max_rate_hz_)
    return Result::kTooSoon;
  try {
    *image = output_ == Output::kYuv ? imageToYuv(msg, max_pixels_) : imageToBgr8(msg, max_pixels_);
  } catch (const std::exception& e) {  // ImageFormatError, and cv::Exception or bad_alloc
    ROS_ERROR_THROTTLE(10.0, "%s: image dropped: %s", node_.c_str(), e.what());
    ++bad_images_;
    return Result::kBadImage;
  }
  last_processed_ = msg.header.stamp;
  return Result::kProcess;
}

}  // namespace adaptive_perception::ros_conv
