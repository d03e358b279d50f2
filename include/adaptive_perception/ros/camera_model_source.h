#pragma once
// The camera model of an image-consuming node (color_estimator, rbpf_localizer), from
// camera/camera_info: its intrinsics, and when the camera_info has lens distortion
// image_geometry's PinholeCameraModel, which rectifies each image (the model is then the
// rectified camera, camera_info's P). Without a camera_info the node waits and says so, unless
// ~camera_model names a camera to assume until one arrives: "aibo_ers7" (the AIBO ERS-7's 208x160
// camera) or a camera file (world/robot_camera.h, e.g. config/cameras/nao_v6_top.yaml: its
// intrinsics; relative paths from the package). Not thread-safe: call under the node's mutex.
#include <image_geometry/pinhole_camera_model.h>
#include <sensor_msgs/CameraInfo.h>

#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/world/camera_model.h"

namespace adaptive_perception::ros_conv {

class CameraModelSource {
 public:
  /// `node` prefixes the log messages; `assumed` is ~camera_model: "" (wait for camera_info),
  /// "aibo_ers7" or a camera file (a value ending in .yaml). Throws std::invalid_argument naming the
  /// allowed values, std::runtime_error naming the file and line of a bad camera file.
  CameraModelSource(std::string node, const std::string& assumed);
  /// The ~camera_model row of the node's parameter table.
  static config::ParameterDoc parameter();
  /// Takes a camera_info; returns true when the model changed (the node rebuilds what depends on
  /// it). A malformed message or an unsupported distortion model is logged (throttled) and
  /// ignored.
  bool onCameraInfo(const sensor_msgs::CameraInfo& info);
  /// True when a model for a width x height image is known; otherwise logs why (waiting for
  /// camera_info, or the size disagrees with it) and the frame should be dropped.
  bool readyFor(int width_px, int height_px);
  /// Whether a model is known (from camera_info or ~camera_model).
  bool known() const { return camera_.has_value(); }
  const world::PinholeCamera& camera() const { return *camera_; }
  /// The image as the model sees it: rectified when the camera_info has distortion, else as is.
  cv::Mat rectify(const cv::Mat& image) const;

 private:
  std::string node_;
  std::optional<world::PinholeCamera> assumed_;  // from ~camera_model
  std::string assumed_name_;
  std::optional<world::PinholeCamera> camera_;
  bool from_camera_info_ = false;
  bool distorted_ = false;
  image_geometry::PinholeCameraModel rectifier_;  // used when distorted_
};

}  // namespace adaptive_perception::ros_conv
