#pragma once
// The shared main() of every node: init, construct the Node class from the public and private node
// handles, spin with `threads` threads; a construction error (bad parameter, bad file) is reported
// with ROS_FATAL and exit status 1.
//
// `lifetime` outlives the node's handles on purpose: roscpp shuts the node down (rosconsole included) when
// the last NodeHandle is destroyed, so without it the ROS_FATAL of a constructor that threw printed nothing.
#include <ros/ros.h>

#include <exception>

namespace adaptive_perception {

template <typename Node>
int runNode(int argc, char** argv, const char* name, int threads = 1) {
  ros::init(argc, argv, name);
  ros::NodeHandle lifetime;
  try {
    Node node(ros::NodeHandle(), ros::NodeHandle("~"));
    if (threads <= 1) {
      ros::spin();
    } else {
      ros::AsyncSpinner spinner(threads);
      spinner.start();
      ros::waitForShutdown();
    }
  } catch (const std::exception& e) {
    ROS_FATAL("%s: %s", name, e.what());
    return 1;
  }
  return 0;
}

}  // namespace adaptive_perception
