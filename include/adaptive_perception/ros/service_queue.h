#pragma once
// Services answered from their own callback queue and thread. A node's data callbacks may be slow
// (a step of the filter, a wait for tf) or stuck behind a full queue; a service advertised through
// ServiceQueue::handle() still answers meanwhile. Handlers run concurrently with the data
// callbacks, so they take the node's mutex as those do.
//
// Declare the ServiceQueue after the state its handlers use and before the ros::ServiceServer
// members: the servers are then destroyed first (roscpp waits for a running handler), then the
// thread stops, then the state goes.
#include <ros/callback_queue.h>
#include <ros/ros.h>

namespace adaptive_perception::ros_conv {

class ServiceQueue {
 public:
  ServiceQueue() : spinner_(1, &queue_) { spinner_.start(); }
  ServiceQueue(const ServiceQueue&) = delete;
  ServiceQueue& operator=(const ServiceQueue&) = delete;
  ~ServiceQueue() { spinner_.stop(); }

  /// A copy of `nh` (same namespace) whose services and subscriptions go to this queue.
  ros::NodeHandle handle(const ros::NodeHandle& nh) {
    ros::NodeHandle h(nh);
    h.setCallbackQueue(&queue_);
    return h;
  }

 private:
  ros::CallbackQueue queue_;
  ros::AsyncSpinner spinner_;
};

}  // namespace adaptive_perception::ros_conv
