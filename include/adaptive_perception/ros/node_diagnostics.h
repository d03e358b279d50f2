#pragma once
// A node's /diagnostics, set up one way for every node: a diagnostic_updater::Updater named after
// the node, the rate of the node's main input (a FrequencyStatus: a window of 10 events, 10%
// tolerance on the node's own bounds), the node's own checks, and a heartbeat.
//
// The heartbeat publishes on a wall-clock timer, not only after an input was taken: with its input
// missing, refused or waiting for tf, a node still reports (its frequency status then says "No
// events recorded" or too low a rate, and its own checks say what they saw). The timer runs in the
// node handle's callback queue, on the thread of the node's data callbacks; a node whose services
// run on their own thread (ros/service_queue.h) passes the mutex those take, and the update runs
// under it. A steady timer: a stopped or replayed /clock does not stop it.
#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/update_functions.h>
#include <ros/ros.h>

#include <mutex>
#include <string>

namespace adaptive_perception::ros_conv {

class NodeDiagnostics {
 public:
  /// `node`: the hardware id; the main input's rate is expected within [min_rate_hz, max_rate_hz];
  /// `state_mutex`: the node's lock, when its services run on their own thread. The heartbeat
  /// starts now.
  NodeDiagnostics(ros::NodeHandle nh, const std::string& node, double min_rate_hz,
                  double max_rate_hz, std::mutex* state_mutex = nullptr)
      : min_rate_hz_(min_rate_hz),
        max_rate_hz_(max_rate_hz),
        rate_(diagnostic_updater::FrequencyStatusParam(&min_rate_hz_, &max_rate_hz_, 0.1, 10)) {
    updater_.setHardwareID(node);
    updater_.add(rate_);
    // The heartbeat: an update every second of wall time (under the node's lock when given), so
    // that the diagnostics speak even when no input arrives.
    heartbeat_ = nh.createSteadyTimer(ros::WallDuration(1.0),
                                      [this, state_mutex](const ros::SteadyTimerEvent&) {
                                        if (state_mutex == nullptr) {
                                          updater_.force_update();
                                          return;
                                        }
                                        std::lock_guard<std::mutex> lock(*state_mutex);
                                        updater_.force_update();
                                      });
  }
  NodeDiagnostics(const NodeDiagnostics&) = delete;
  NodeDiagnostics& operator=(const NodeDiagnostics&) = delete;

  /// The node's own check `name`: (node->*check)(status) at every update.
  template <class Node>
  void add(const std::string& name, Node* node,
           void (Node::*check)(diagnostic_updater::DiagnosticStatusWrapper&)) {
    updater_.add(name, node, check);
  }
  /// One main input taken (counts towards the rate).
  void tick() { rate_.tick(); }
  /// Publishes when the updater's period has passed since the last time (call after an input).
  void update() { updater_.update(); }

 private:
  double min_rate_hz_, max_rate_hz_;  // FrequencyStatus reads them through pointers
  diagnostic_updater::Updater updater_;
  diagnostic_updater::FrequencyStatus rate_;
  ros::SteadyTimer heartbeat_;
};

}  // namespace adaptive_perception::ros_conv
