// ground_truth_tf_publisher: see include/adaptive_perception/ros/ground_truth_tf_node.h.
#include <ros/ros.h>

#include "adaptive_perception/ros/ground_truth_tf_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "ground_truth_tf_publisher");
  try {
    adaptive_perception::GroundTruthTfNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("ground_truth_tf_publisher: %s", e.what());
    return 1;
  }
  return 0;
}
