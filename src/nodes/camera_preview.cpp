// camera_preview: see include/adaptive_perception/ros/camera_preview_node.h.
#include <ros/ros.h>

#include "adaptive_perception/ros/camera_preview_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "camera_preview");
  try {
    adaptive_perception::CameraPreviewNode node(ros::NodeHandle(), ros::NodeHandle("~"));
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("camera_preview: %s", e.what());
    return 1;
  }
  return 0;
}
