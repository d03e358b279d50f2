#include "adaptive_perception/ros/camera_preview_node.h"

#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/ros/node_run.h"

namespace adaptive_perception {

std::vector<config::ParameterDoc> CameraPreviewNode::parameters() {
  return {ros_params::imageTransportParameter()};
}

CameraPreviewNode::CameraPreviewNode(ros::NodeHandle nh, ros::NodeHandle pnh) {
  image_transport::ImageTransport it(nh);
  image_pub_ = it.advertise("camera/image_preview", 2);
  labels_pub_ = it.advertise("camera/labels_color", 2);
  image_sub_ = it.subscribe(ros_topics::kCameraImage, 2, &CameraPreviewNode::onImage, this,
                            ros_params::imageTransportHints(pnh));
  // Class ids must arrive exactly: the labels are always raw.
  labels_sub_ = nh.subscribe(ros_topics::kCameraLabels, 2, &CameraPreviewNode::onLabels, this);
}

void CameraPreviewNode::onImage(const sensor_msgs::ImageConstPtr& msg) {
  if (image_pub_.getNumSubscribers() == 0) return;
  try {
    const cv::Mat bgr = color::yuvToBgr(ros_conv::imageToYuv(*msg));
    image_pub_.publish(ros_conv::bgr8ToImage(bgr, msg->header));
  } catch (const std::exception& e) {  // ImageFormatError, and cv::Exception or bad_alloc
    ROS_ERROR_THROTTLE(10.0, "camera_preview: frame dropped: %s", e.what());
  }
}

void CameraPreviewNode::onLabels(const sensor_msgs::ImageConstPtr& msg) {
  if (labels_pub_.getNumSubscribers() == 0) return;
  try {
    labels_pub_.publish(
        ros_conv::bgr8ToImage(color::colorizeLabels(ros_conv::imageToMono8(*msg)), msg->header));
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(10.0, "camera_preview: labels dropped: %s", e.what());
  }
}

// The node's main (src/nodes, ros/node_main.h) links this one instance.
template int runNode<CameraPreviewNode>(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
