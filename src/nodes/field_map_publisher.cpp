// field_map_publisher: see include/adaptive_perception/ros/field_map_publisher_node.h.
#include <ros/ros.h>

#include "adaptive_perception/ros/field_map_publisher_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "field_map_publisher");
  try {
    adaptive_perception::FieldMapPublisherNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("field_map_publisher: %s", e.what());
    return 1;
  }
  return 0;
}
