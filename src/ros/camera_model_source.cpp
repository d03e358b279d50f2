#include "adaptive_perception/ros/camera_model_source.h"

#include <ros/console.h>

#include <stdexcept>

#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/world/robot_camera.h"

namespace adaptive_perception::ros_conv {

namespace {
constexpr char kAibo[] = "aibo_ers7";
}  // namespace

CameraModelSource::CameraModelSource(std::string node, const std::string& assumed)
    : node_(std::move(node)) {
  const auto ends_with = [&](const std::string& tail) {
    return assumed.size() >= tail.size() &&
           assumed.compare(assumed.size() - tail.size(), tail.size(), tail) == 0;
  };
  if (assumed == kAibo) {
    assumed_ = world::PinholeCamera::aiboErs7();
    assumed_name_ = "the AIBO ERS-7 camera";
  } else if (ends_with(".yaml") || ends_with(".yml")) {
    const world::RobotCamera file =
        world::RobotCamera::loadYaml(ros_params::resolvePackagePath(assumed));
    assumed_ = file.camera;
    assumed_name_ = file.name + " (" + assumed + ")";
  } else if (!assumed.empty()) {
    throw std::invalid_argument("camera_model = '" + assumed +
                                "' (allowed: empty, to wait for camera_info, aibo_ers7, or a "
                                "camera file NAME.yaml such as config/cameras/nao_v6_top.yaml)");
  }
}

config::ParameterDoc CameraModelSource::parameter() {
  return {"camera_model", "string", "", "(empty), aibo_ers7, a camera file",
          "the camera assumed until a camera_info arrives: empty waits for camera/camera_info "
          "(and says so); aibo_ers7 the AIBO ERS-7's 208x160 camera; a camera file (.yaml, "
          "config/cameras/, relative from the package) its intrinsics"};
}

bool CameraModelSource::onCameraInfo(const sensor_msgs::CameraInfo& info) {
  try {
    const world::PinholeCamera cam = fromCameraInfo(info);
    const bool distorted = hasDistortion(info);
    if (camera_ && from_camera_info_ && cam.width_px == camera_->width_px &&
        cam.height_px == camera_->height_px && cam.fx_px == camera_->fx_px &&
        cam.fy_px == camera_->fy_px && cam.cx_px == camera_->cx_px && cam.cy_px == camera_->cy_px &&
        distorted == distorted_ && (!distorted || info.D == rectifier_.cameraInfo().D))
      return false;
    if (distorted) {
      if (info.distortion_model != "plumb_bob" && info.distortion_model != "rational_polynomial" &&
          info.distortion_model != "equidistant")
        throw std::invalid_argument("distortion model '" + info.distortion_model +
                                    "' is not supported (plumb_bob, rational_polynomial, "
                                    "equidistant)");
      rectifier_.fromCameraInfo(info);
      ROS_INFO("%s: camera_info has %s distortion: images are rectified", node_.c_str(),
               info.distortion_model.c_str());
    }
    distorted_ = distorted;
    camera_ = cam;
    from_camera_info_ = true;
    return true;
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(10.0, "%s: camera_info ignored: %s", node_.c_str(), e.what());
    return false;
  }
}

bool CameraModelSource::readyFor(int width, int height) {
  if (!camera_) {
    if (!assumed_ || width != assumed_->width_px || height != assumed_->height_px) {
      ROS_WARN_THROTTLE(
          5.0, "%s: waiting for camera/camera_info (image is %dx%d; ~camera_model %s)",
          node_.c_str(), width, height,
          assumed_ ? ("is " + assumed_name_ + ", " + std::to_string(assumed_->width_px) + "x" +
                      std::to_string(assumed_->height_px))
                         .c_str()
                   : "names none: aibo_ers7 or a camera file would assume one");
      return false;
    }
    camera_ = assumed_;
    ROS_INFO("%s: no camera_info yet: %s (~camera_model)", node_.c_str(), assumed_name_.c_str());
  }
  if (camera_->width_px != width || camera_->height_px != height) {
    ROS_ERROR_THROTTLE(5.0, "%s: image is %dx%d but %s says %dx%d: frame dropped", node_.c_str(),
                       width, height, from_camera_info_ ? "camera_info" : "~camera_model",
                       camera_->width_px, camera_->height_px);
    return false;
  }
  return true;
}

cv::Mat CameraModelSource::rectify(const cv::Mat& image) const {
  if (!distorted_) return image;
  cv::Mat out;
  rectifier_.rectifyImage(image, out, cv::INTER_LINEAR);
  return out;
}

}  // namespace adaptive_perception::ros_conv
