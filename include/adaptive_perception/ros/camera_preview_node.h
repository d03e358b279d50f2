#pragma once
// camera_preview: makes the camera stream viewable in rviz, which cannot show yuv422. Converts
// every image on camera/image_raw (yuv422, bgr8 or rgb8) to bgr8, and colourises true labels
// (simulator bags) with the class display colours.
//
// Parameters: none.
// Subscribed:
//   camera/image_raw (sensor_msgs/Image): yuv422 | bgr8 | rgb8; another encoding gets one throttled
//   error
//       naming it and the frame is dropped.
//   camera/labels (sensor_msgs/Image, mono8): class ids (0 green .. 5 orange, 255 background).
// Published:
//   camera/image_preview (sensor_msgs/Image, bgr8), camera/labels_color (sensor_msgs/Image, bgr8),
//   both with the input's header.
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include <opencv2/core.hpp>

namespace adaptive_perception {

class CameraPreviewNode {
 public:
  CameraPreviewNode(ros::NodeHandle nh, ros::NodeHandle pnh);

 private:
  void onImage(const sensor_msgs::ImageConstPtr& msg);
  void onLabels(const sensor_msgs::ImageConstPtr& msg);
  ros::Subscriber image_sub_, labels_sub_;
  ros::Publisher image_pub_, labels_pub_;
};

}  // namespace adaptive_perception
