#pragma once
// camera_preview: makes the camera stream viewable in rviz, which cannot show yuv422. Converts
// every image on camera/image_raw (yuv422, bgr8 or rgb8) to bgr8, and colourises true labels
// (simulator bags) with the class display colours.
//
// Its interface (parameters, subscribed and published topics, services, tf) is documented once,
// in docs/nodes/camera_preview.md; the parameter table there is made from parameters().
#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/config/fields.h"

namespace adaptive_perception {

class CameraPreviewNode {
 public:
  CameraPreviewNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Every private parameter the node reads (its doc page's table).
  static std::vector<config::ParameterDoc> parameters();

 private:
  void onImage(const sensor_msgs::ImageConstPtr& msg);
  void onLabels(const sensor_msgs::ImageConstPtr& msg);
  image_transport::Subscriber image_sub_;
  ros::Subscriber labels_sub_;
  image_transport::Publisher image_pub_, labels_pub_;
};

}  // namespace adaptive_perception
