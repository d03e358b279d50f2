#pragma once
// The definition of runNode (ros/node_main.h): init, construct the Node class from the public and
// private node handles, spin with callbackThreads<Node>() threads; a construction error (bad
// parameter, bad file) is reported with ROS_FATAL and exit status 1. Each node's source file
// includes this and instantiates runNode for its class once; ros/node_nodelet.h runs the same
// classes as nodelets.
//
// `lifetime` outlives the node's handles on purpose: roscpp shuts the node down (rosconsole
// included) when the last NodeHandle is destroyed, so without it the ROS_FATAL of a constructor
// that threw printed nothing.
#include <ros/ros.h>

#include <exception>
#include <type_traits>

#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {

/// How many of a node's callbacks may run at once: Node::kCallbackThreads where the Node class
/// declares it (a node that locks its own state, so that a slow image does not hold up tf or a
/// service), else 1 (callbacks one at a time).
template <typename Node, typename = void>
struct CallbackThreads : std::integral_constant<int, 1> {};
template <typename Node>
struct CallbackThreads<Node, std::void_t<decltype(Node::kCallbackThreads)>>
    : std::integral_constant<int, Node::kCallbackThreads> {};
template <typename Node>
constexpr int callbackThreads() {
  return CallbackThreads<Node>::value;
}

template <typename Node>
int runNode(int argc, char** argv, const char* name) {
  ros::init(argc, argv, name);
  ros::NodeHandle lifetime;
  try {
    Node node(ros::NodeHandle(), ros::NodeHandle("~"));
    if (callbackThreads<Node>() <= 1) {
      ros::spin();
    } else {
      ros::AsyncSpinner spinner(callbackThreads<Node>());
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
