#include "adaptive_perception/ros/camera_model_source.h"

#include <ros/console.h>

#include "adaptive_perception/ros/msg_conversion.h"

namespace adaptive_perception::ros_conv {

bool CameraModelSource::onCameraInfo(const sensor_msgs::CameraInfo& info) {
  try {
    const world::PinholeCamera cam = fromCameraInfo(info);
    if (camera_ && cam.width_px == camera_->width_px && cam.height_px == camera_->height_px &&
        cam.fx_px == camera_->fx_px && cam.fy_px == camera_->fy_px && cam.cx_px == camera_->cx_px &&
        cam.cy_px == camera_->cy_px)
      return false;
    camera_ = cam;
    return true;
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(10.0, "%s: camera_info ignored: %s", node_.c_str(), e.what());
    return false;
  }
}

bool CameraModelSource::readyFor(int width, int height) {
  if (!camera_) {
    if (width != 208 || height != 160) {
      ROS_WARN_THROTTLE(5.0, "%s: waiting for camera/camera_info (image is %dx%d)", node_.c_str(),
                        width, height);
      return false;
    }
    camera_ = world::PinholeCamera::aiboErs7();
  }
  if (camera_->width_px != width || camera_->height_px != height) {
    ROS_ERROR_THROTTLE(5.0, "%s: image is %dx%d but camera_info says %dx%d: frame dropped",
                       node_.c_str(), width, height, camera_->width_px, camera_->height_px);
    return false;
  }
  return true;
}

}  // namespace adaptive_perception::ros_conv
