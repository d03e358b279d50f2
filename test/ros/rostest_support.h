#pragma once
// Small pieces shared by the rostests in test/ros: waiting on the wall clock (the tests run under
// use_sim_time, where ros::Time stands still between bags) and reading the std_msgs/Header that
// starts most messages without knowing their type.
#include <ros/ros.h>
#include <ros/serialization.h>
#include <std_msgs/Header.h>
#include <std_msgs/String.h>
#include <topic_tools/shape_shifter.h>

#include "adaptive_perception/ros/message_header.h"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace adaptive_perception::rostest_support {

struct CommandRun {
  int status = -1;  // exit status; -1 when killed by the timeout or a signal
  std::string output;  // stdout and stderr together
};

/// Runs `command` through the shell for at most `timeout_s` seconds (then SIGKILL).
inline CommandRun runCommand(const std::string& command, int timeout_s = 30) {
  const std::string cmd =
      "timeout -s KILL " + std::to_string(timeout_s) + " " + command + " 2>&1";
  CommandRun r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe)) r.output += buf.data();
  const int st = ::pclose(pipe);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

/// Polls `done` every `poll_s` seconds of wall time until it returns true, ROS shuts down or
/// `timeout_s` passes; returns the last value of `done`.
inline bool waitUntil(const std::function<bool()>& done, double timeout_s, double poll_s = 0.05) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (ros::ok() && ros::WallTime::now() < deadline) {
    if (done()) return true;
    ros::WallDuration(poll_s).sleep();
  }
  return done();
}

/// What a test heard on one topic: the last message, how many came and, when asked, all of them
/// (thread-safe; the callbacks run on the test's spinner).
template <class M>
class TopicRecord {
 public:
  using Ptr = boost::shared_ptr<const M>;
  TopicRecord(ros::NodeHandle& nh, const std::string& topic, uint32_t queue_size,
              bool keep_all = false)
      : keep_all_(keep_all), sub_(nh.subscribe<M>(topic, queue_size, [this](const Ptr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          last_ = m;
          ++count_;
          if (keep_all_) all_.push_back(m);
        })) {}
  Ptr last() const {
    std::lock_guard<std::mutex> l(mutex_);
    return last_;
  }
  int count() const {
    std::lock_guard<std::mutex> l(mutex_);
    return count_;
  }
  std::vector<Ptr> all() const {
    std::lock_guard<std::mutex> l(mutex_);
    return all_;
  }

 private:
  mutable std::mutex mutex_;
  Ptr last_;
  int count_ = 0;
  bool keep_all_;
  std::vector<Ptr> all_;
  ros::Subscriber sub_;
};

/// The string last published on `topic` (a player script's /test_phase), thread-safe.
class PhaseListener {
 public:
  explicit PhaseListener(ros::NodeHandle& nh, const std::string& topic = "test_phase")
      : sub_(nh.subscribe<std_msgs::String>(topic, 5, [this](const std_msgs::StringConstPtr& m) {
          std::lock_guard<std::mutex> l(mutex_);
          phase_ = m->data;
        })) {}
  std::string phase() const {
    std::lock_guard<std::mutex> l(mutex_);
    return phase_;
  }
  /// True when `phase` was announced within `timeout_s` seconds of wall time.
  bool waitFor(const std::string& phase, double timeout_s) const {
    return waitUntil([&] { return this->phase() == phase; }, timeout_s, 0.2);
  }

 private:
  mutable std::mutex mutex_;
  std::string phase_;
  ros::Subscriber sub_;
};

// Reading the Header of a message of any type (adaptive_perception/ros/message_header.h).
using ros_messages::leadingHeader;
using ros_messages::serialized;

}  // namespace adaptive_perception::rostest_support
