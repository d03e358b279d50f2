#include "adaptive_perception/ros/stamp_order.h"

#include <algorithm>

namespace adaptive_perception::ros_conv {

StampOrder::Verdict StampOrder::check(const ros::Time& stamp, const std::string& publisher) {
  const ros::Time clock = ros::Time::now();
  const bool clock_went_back = !last_clock_.isZero() && clock < last_clock_;
  last_clock_ = clock;
  if (last_stamp_.isZero() || stamp >= last_stamp_) {
    last_stamp_ = stamp;
    last_publisher_ = publisher;
    return Verdict::kTake;
  }
  const double back_s = (last_stamp_ - stamp).toSec();
  if (clock_went_back || back_s > config_.restart_after_back_s) {
    ROS_WARN(
        "%s: %s time went backwards by %.3f s (%s): starting again", node_.c_str(), input_.c_str(),
        back_s,
        clock_went_back ? "the clock jumped back: bag looped?" : "more than time_back_restart_s");
    last_stamp_ = stamp;
    last_publisher_ = publisher;
    // The restart answers the clock's jump too: when /clock arrives after this message (another
    // connection), the jump it shows must not restart the next one again.
    last_clock_ = std::min(clock, stamp);
    ++restarts_;
    return Verdict::kRestart;
  }
  ++dropped_;
  // Images through image_transport come without their publisher's name.
  const std::string from =
      publisher.empty() && last_publisher_.empty()
          ? ""
          : " (from " + (publisher.empty() ? "?" : publisher) + "; the last from " +
                (last_publisher_.empty() ? "?" : last_publisher_) +
                (publisher != last_publisher_ ? ": two publishers interleave?" : "") + ")";
  ROS_WARN_THROTTLE(10.0,
                    "%s: %s message %.3f s older than the last one dropped%s; %ld dropped so far",
                    node_.c_str(), input_.c_str(), back_s, from.c_str(), dropped_);
  return Verdict::kDrop;
}

}  // namespace adaptive_perception::ros_conv
