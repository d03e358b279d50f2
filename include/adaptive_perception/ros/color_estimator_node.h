#pragma once
// color_estimator: adaptive colour classification with the hierarchical Bayesian colour model and a
// switching Kalman filter over lighting (Schulz & Fox 2004, section III), given the camera pose;
// with ~pose_free, images that have no pose yet are segmented without one (field, lines).
//
// Its interface (parameters, subscribed and published topics, services, tf) is documented once,
// in docs/nodes/color_estimator.md; the parameter table there is made from parameters().
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>

#include <memory>
#include <mutex>
#include <optional>

#include "adaptive_perception/ColorEstimatorConfig.h"
#include "adaptive_perception/SavePrior.h"
#include "adaptive_perception/color/color_estimator.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/ros/field_camera_input.h"
#include "adaptive_perception/ros/service_queue.h"
#include "adaptive_perception/ros/stamp_order.h"
#include "adaptive_perception/ros/node_diagnostics.h"

namespace adaptive_perception {

class ColorEstimatorNode {
 public:
  /// Throws ros_params::ParamError / std::runtime_error (bad prior file) with a clear message.
  ColorEstimatorNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Callbacks that may run at once (node_run.h): the state is locked, so tf and camera_info
  /// are taken while an image is classified.
  static constexpr int kCallbackThreads = 2;
  /// Every private parameter the node reads (its doc page's table).
  static std::vector<config::ParameterDoc> parameters();

 private:
  void onImage(const sensor_msgs::ImageConstPtr& msg);
  void onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg);
  /// ~pose_free: an image without a camera pose, segmented by color::segmentFieldYuv.
  void classifyWithoutPose(const sensor_msgs::Image& msg, const cv::Mat& yuv);
  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  bool onSavePrior(SavePrior::Request& req, SavePrior::Response& res);
  void onReconfigure(adaptive_perception::ColorEstimatorConfig& config, uint32_t level);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);
  bool ensureEstimator(int width, int height);

  std::mutex mutex_;
  color::ColorEstimatorConfig config_;
  ros_conv::FieldCameraInput input_;
  std::unique_ptr<color::ColorEstimator> estimator_;

  ros::Publisher model_pub_;
  image_transport::Publisher classified_pub_, classified_color_pub_;
  // reset, save_prior and dynamic_reconfigure answer while an image waits for tf.
  ros_conv::ServiceQueue service_queue_;
  ros::ServiceServer reset_srv_, save_srv_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<adaptive_perception::ColorEstimatorConfig>>
      reconfigure_;
  long frames_ = 0;
  long pose_free_frames_ = 0;
  double last_log_likelihood_ = 0.0;
  ros_conv::NodeDiagnostics diagnostics_;  // last: its heartbeat stops before the state it reads goes
};

}  // namespace adaptive_perception
