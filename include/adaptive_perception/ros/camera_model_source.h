#pragma once
// The camera model of an image-consuming node: from camera/camera_info when one has arrived, else
// the AIBO ERS-7 camera for 208x160 images. Shared by color_estimator and rbpf_localizer. Not
// thread-safe: call under the node's mutex.
#include <sensor_msgs/CameraInfo.h>

#include <optional>
#include <string>

#include "adaptive_perception/world/camera_model.h"

namespace adaptive_perception::ros_conv {

class CameraModelSource {
 public:
  /// `node` prefixes the log messages.
  explicit CameraModelSource(std::string node) : node_(std::move(node)) {}
  /// Takes a camera_info; returns true when the model changed (the node rebuilds what depends on
  /// it). A malformed message is logged (throttled) and ignored.
  bool onCameraInfo(const sensor_msgs::CameraInfo& info);
  /// True when a model for a width x height image is known; otherwise logs why (waiting for
  /// camera_info, or the size disagrees with it) and the frame should be dropped.
  bool readyFor(int width_px, int height_px);
  /// Whether a model is known (from camera_info or the 208x160 default).
  bool known() const { return camera_.has_value(); }
  const world::PinholeCamera& camera() const { return *camera_; }

 private:
  std::string node_;
  std::optional<world::PinholeCamera> camera_;
};

}  // namespace adaptive_perception::ros_conv
