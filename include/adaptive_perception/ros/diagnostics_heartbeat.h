#pragma once
// A node's /diagnostics published on a wall-clock timer, not only after an input was taken: with
// its input missing, refused or waiting for tf, a node still reports (its frequency status then
// says "No events recorded" or too low a rate, and its own checks say what they saw). The timer
// runs in the node handle's callback queue, on the thread of the node's data callbacks; a node
// whose services run on their own thread (ros/service_queue.h) passes the mutex those take, and
// the update runs under it. A steady timer: a stopped or replayed /clock does not stop it.
#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include <mutex>

namespace adaptive_perception::ros_conv {

/// Starts the heartbeat: `updater->force_update()` every `period_s` seconds of wall time (under
/// `state_mutex` when given). Keep the returned timer as long as the updater and the mutex live.
inline ros::SteadyTimer diagnosticsHeartbeat(ros::NodeHandle& nh,
                                             diagnostic_updater::Updater* updater,
                                             std::mutex* state_mutex = nullptr,
                                             double period_s = 1.0) {
  return nh.createSteadyTimer(
      ros::WallDuration(period_s), [updater, state_mutex](const ros::SteadyTimerEvent&) {
        if (state_mutex == nullptr) {
          updater->force_update();
          return;
        }
        std::lock_guard<std::mutex> lock(*state_mutex);
        updater->force_update();
      });
}

}  // namespace adaptive_perception::ros_conv
