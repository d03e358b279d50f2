#pragma once
// The input side that color_estimator and rbpf_localizer share: a robot's camera on a known
// RoboCup field under changing light. It loads and documents the parameters both read, and holds
// what they both keep:
//   - the field (~field_file) and the lighting priors (~filter, ~priors, ~single_prior,
//     ~priors_dir: ros_params::loadLightingPriors);
//   - the camera model (camera/camera_info, or ~camera_model until one comes: CameraModelSource);
//   - the image intake (camera/image through ~image_transport, two deep; ImageGate: stamp order
//     with ~time_back_restart_s, conversion to YUV, bad images counted);
//   - the tf lookups at an image's stamp (~tf_timeout_s: MeasurementTf) and ~map_frame;
//   - the counts every such node reports in its diagnostics.
// Not thread-safe except tf(): the node calls it under its own lock.
#include <diagnostic_updater/diagnostic_updater.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <string>
#include <vector>

#include "adaptive_perception/color/color_model.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/ros/camera_model_source.h"
#include "adaptive_perception/ros/image_gate.h"
#include "adaptive_perception/ros/measurement_tf.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/world/field_map.h"

namespace adaptive_perception::ros_conv {

class FieldCameraInput {
 public:
  /// `node` names the node in its logs. Loads the parameters from `pnh`; throws
  /// ros_params::ParamError naming a wrong one (a bad prior or field file: std::runtime_error
  /// naming the file). `default_tf_timeout_s` is the node's default for ~tf_timeout_s.
  FieldCameraInput(const std::string& node, const ros::NodeHandle& pnh,
                   double default_tf_timeout_s);
  /// The rows of these parameters in the node's table; `tf_what` names the transforms the node
  /// waits for.
  static std::vector<config::ParameterDoc> parameters(double default_tf_timeout_s,
                                                      const std::string& tf_what);

  /// Subscribes node->on_image to camera/image (two deep: an image re-sent older right after a
  /// newer one is dropped rather than displacing the newer one) and node->on_info to
  /// camera/camera_info.
  template <class Node>
  void subscribe(ros::NodeHandle nh, void (Node::*on_image)(const sensor_msgs::ImageConstPtr&),
                 void (Node::*on_info)(const sensor_msgs::CameraInfoConstPtr&), Node* node) {
    image_sub_ = image_transport::ImageTransport(nh).subscribe(ros_topics::kCameraImage, 2, on_image,
                                                               node, hints_);
    info_sub_ = nh.subscribe(ros_topics::kCameraInfo, 1, on_info, node);
  }

  /// True when the camera model is known and fits a width x height image; an image whose size
  /// disagrees with camera_info counts as bad.
  bool readyFor(int width_px, int height_px);
  /// Counts an image the node could not use.
  void countBadImage() { ++bad_images_; }
  /// The counts of the intake: frames skipped for want of tf, dropped as older than the last, bad.
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) const;
  /// "<filter> filter with N prior(s) from <dir>", for the node's start-up line.
  std::string priorsSummary() const;

  const world::FieldMap& field() const { return field_; }
  const std::vector<color::LightingPrior>& priors() const { return priors_; }
  const std::string& mapFrame() const { return map_frame_; }
  CameraModelSource& camera() { return camera_; }
  const CameraModelSource& camera() const { return camera_; }
  ImageGate& gate() { return gate_; }
  MeasurementTf& tf() { return tf_; }

 private:
  CameraModelSource camera_;
  MeasurementTf tf_;
  ImageGate gate_;
  std::string filter_, priors_dir_;  // set by loading priors_, so declared before it
  std::vector<color::LightingPrior> priors_;
  world::FieldMap field_;
  std::string map_frame_;
  image_transport::TransportHints hints_;
  image_transport::Subscriber image_sub_;
  ros::Subscriber info_sub_;
  long bad_images_ = 0;
};

}  // namespace adaptive_perception::ros_conv
