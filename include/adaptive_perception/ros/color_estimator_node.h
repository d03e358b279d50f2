#pragma once
// color_estimator: adaptive colour classification with the hierarchical Bayesian colour model and a
// switching Kalman filter over lighting (Schulz & Fox 2004, section III), given the camera pose.
//
// Its interface (parameters, subscribed and published topics, services, tf) is documented once,
// in docs/nodes/color_estimator.md; the parameter table there is made from parameters().
#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/update_functions.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <memory>
#include <mutex>
#include <optional>

#include "adaptive_perception/ColorEstimatorConfig.h"
#include "adaptive_perception/SavePrior.h"
#include "adaptive_perception/color/color_estimator.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/ros/camera_model_source.h"
#include "adaptive_perception/ros/image_gate.h"
#include "adaptive_perception/ros/service_queue.h"
#include "adaptive_perception/ros/stamp_order.h"

namespace adaptive_perception {

class ColorEstimatorNode {
 public:
  /// Throws ros_params::ParamError / std::runtime_error (bad prior file) with a clear message.
  ColorEstimatorNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Callbacks that may run at once (node_main.h): the state is locked, so tf and camera_info
  /// are taken while an image is classified.
  static constexpr int kCallbackThreads = 2;
  /// Every private parameter the node reads (its doc page's table).
  static std::vector<config::ParameterDoc> parameters();

 private:
  void onImage(const sensor_msgs::ImageConstPtr& msg);
  void onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg);
  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onSavePrior(SavePrior::Request& req, SavePrior::Response& res);
  void onReconfigure(adaptive_perception::ColorEstimatorConfig& config, uint32_t level);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);
  bool ensureEstimator(int width, int height);

  ros::NodeHandle nh_, pnh_;
  std::mutex mutex_;
  color::ColorEstimatorConfig config_;
  std::vector<color::LightingPrior> priors_;
  world::FieldMap map_;
  ros_conv::CameraModelSource camera_;
  std::unique_ptr<color::ColorEstimator> estimator_;
  std::string map_frame_;
  double tf_timeout_s_ = 0.0;  // from ~tf_timeout_s
  ros_conv::ImageGate gate_{"color_estimator", 0.0, {}, ros_conv::ImageGate::Output::kYuv};

  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  image_transport::Subscriber image_sub_;
  ros::Subscriber info_sub_;
  ros::Publisher model_pub_;
  image_transport::Publisher classified_pub_, classified_color_pub_;
  // reset, save_prior and dynamic_reconfigure answer while an image waits for tf.
  ros_conv::ServiceQueue service_queue_;
  ros::ServiceServer reset_srv_, save_srv_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<adaptive_perception::ColorEstimatorConfig>>
      reconfigure_;
  diagnostic_updater::Updater diagnostics_;
  ros::SteadyTimer diagnostics_timer_;  // ros/diagnostics_heartbeat.h: reports with no input too
  double min_freq_ = 0.5, max_freq_ = 100.0;
  std::unique_ptr<diagnostic_updater::FrequencyStatus> freq_;
  long frames_ = 0, skipped_no_tf_ = 0, skipped_bad_image_ = 0;
  double last_log_likelihood_ = 0.0;
};

}  // namespace adaptive_perception
