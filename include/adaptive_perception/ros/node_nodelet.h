#pragma once
// Every node's class as a nodelet (the same classes node_main.h runs as executables): onInit
// constructs the Node from the nodelet's public and private node handles, the manager's
// multi-threaded ones when callbackThreads<Node>() > 1 (as the executable spins that many threads),
// else the single-threaded ones (callbacks one at a time, as ros::spin). Messages between nodelets
// in one manager pass as shared pointers, without copies. A construction error (bad parameter, bad
// file) is logged with NODELET_FATAL naming the nodelet, and the load fails.
#include <nodelet/nodelet.h>

#include <exception>
#include <memory>

#include "adaptive_perception/ros/node_run.h"

namespace adaptive_perception {

template <typename Node>
class NodeNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    try {
      if (callbackThreads<Node>() > 1)
        node_ = std::make_unique<Node>(getMTNodeHandle(), getMTPrivateNodeHandle());
      else
        node_ = std::make_unique<Node>(getNodeHandle(), getPrivateNodeHandle());
    } catch (const std::exception& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
  }
  std::unique_ptr<Node> node_;
};

}  // namespace adaptive_perception
