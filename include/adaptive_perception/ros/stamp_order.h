#pragma once
// The order of one input stream's stamps. A message older than the last one taken is dropped (a
// second publisher re-sending, a reordering network): it must not restart a filter. The caller
// starts again only when time really went back: the clock itself jumped back (a looped bag under
// use_sim_time), or the message is older than the last by more than `restart_after_back_s` (a
// bag looped without --clock, a robot restarted). A drop is reported with a throttled warning that
// names the publisher of the old message and of the last one (two publishers that interleave show
// up as two names).
#include <ros/ros.h>

#include <string>

namespace adaptive_perception::ros_conv {

struct StampOrderConfig {
  /// A message older than the last one by more than this many seconds restarts; by less, it is
  /// dropped. Read from ~time_back_restart_s (0.01 .. 3600).
  double restart_after_back_s = 1.0;
};

class StampOrder {
 public:
  /// `node` and `input` name the stream in warnings ("rbpf_localizer", "camera/image_raw").
  StampOrder(std::string node, std::string input, StampOrderConfig config = {})
      : node_(std::move(node)), input_(std::move(input)), config_(config) {}

  enum class Verdict {
    kTake,     // in order (or the first message)
    kDrop,     // older than the last by at most restart_after_back_s, the clock did not go back
    kRestart,  // time went back: the caller starts again, then takes the message
  };
  /// Judges a message with this stamp from this publisher; the last stamp moves on kTake and
  /// kRestart only.
  Verdict check(const ros::Time& stamp, const std::string& publisher);

  /// Forget the last stamp (the next message is taken as the first).
  void clear() { last_stamp_ = ros::Time(); }
  long dropped() const { return dropped_; }
  long restarts() const { return restarts_; }
  const StampOrderConfig& config() const { return config_; }

 private:
  std::string node_, input_;
  StampOrderConfig config_;
  ros::Time last_stamp_, last_clock_;
  std::string last_publisher_;
  long dropped_ = 0, restarts_ = 0;
};

}  // namespace adaptive_perception::ros_conv
