// color_estimator: see include/adaptive_perception/ros/color_estimator_node.h.
#include <ros/ros.h>

#include "adaptive_perception/ros/color_estimator_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "color_estimator");
  try {
    adaptive_perception::ColorEstimatorNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::AsyncSpinner spinner(2);  // images and tf/services in parallel
    spinner.start();
    ros::waitForShutdown();
  } catch (const std::exception& e) {
    ROS_FATAL("color_estimator: %s", e.what());
    return 1;
  }
  return 0;
}
