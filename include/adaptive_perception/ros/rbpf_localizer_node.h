#pragma once
// rbpf_localizer: Rao-Blackwellised particle filter over the robot pose on the field and the
// lighting (Schulz & Fox 2004, section IV). The algorithm is localization::RbpfLocalizer; this node
// feeds it images, odometry and the head chain from tf, and publishes its estimate.
//
// Its interface (parameters, subscribed and published topics, services, tf) is documented once,
// in docs/nodes/rbpf_localizer.md; the parameter table there is made from parameters().
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/transform_broadcaster.h>

#include <limits>
#include <memory>
#include <mutex>
#include <optional>

#include "adaptive_perception/color/color_lut.h"
#include "adaptive_perception/localization/rbpf_localizer.h"
#include "adaptive_perception/ros/field_camera_input.h"
#include "adaptive_perception/ros/node_diagnostics.h"
#include "adaptive_perception/ros/service_queue.h"
#include "adaptive_perception/ros/stamp_order.h"

namespace adaptive_perception {

class RbpfLocalizerNode {
 public:
  /// Throws ros_params::ParamError / std::runtime_error (bad prior or field file) with a clear
  /// message.
  RbpfLocalizerNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Callbacks that may run at once (node_run.h): the state is locked, so tf and camera_info
  /// are taken while an image is weighed.
  static constexpr int kCallbackThreads = 2;
  /// Every private parameter the node reads, with its default, range and doc (the table of
  /// docs/nodes/rbpf_localizer.md, made by describe_parameters).
  static std::vector<config::ParameterDoc> parameters();

 private:
  void onImage(const sensor_msgs::ImageConstPtr& msg);
  void onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg);
  void onInitialPose(const geometry_msgs::PoseWithCovarianceStampedConstPtr& msg);
  bool onGlobalLocalization(std_srvs::Empty::Request& req, std_srvs::Empty::Response& res);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);
  bool ensureLocalizer(int width, int height);
  /// A new filter on the field, camera and priors of input_ (under mutex_).
  std::unique_ptr<localization::RbpfLocalizer> newLocalizer() const;
  void publish(const std_msgs::Header& image_header, const Eigen::Isometry3d& odom_to_base,
               const cv::Mat& yuv);

  std::mutex mutex_;
  localization::RbpfConfig config_;
  ros_conv::FieldCameraInput input_;
  std::unique_ptr<localization::RbpfLocalizer> rbpf_;
  // A pose to start from (initial_pose parameter or initialpose topic), applied when the localizer
  // is (re)built.
  std::optional<std::pair<math::SE2, Eigen::Matrix3d>> pending_pose_;
  std::optional<std::pair<math::SE2, Eigen::Matrix3d>> configured_pose_;  // ~initial_pose
  Eigen::Matrix3d initial_pose_cov_;  // from ~initial_pose_std: an initialpose without covariance
  std::string odom_frame_, base_frame_;
  bool publish_tf_ = true;
  double transform_tolerance_s_ = 0.0;  // from ~transform_tolerance_s
  std::optional<Eigen::Isometry3d> last_odom_;
  ros::Time last_stamp_;
  color::ColorLutCache lut_;

  tf2_ros::TransformBroadcaster tf_broadcaster_;
  ros::Subscriber initial_pose_sub_;
  ros::Publisher pose_pub_, particles_pub_, model_pub_;
  image_transport::Publisher classified_pub_, classified_color_pub_;
  ros_conv::ServiceQueue service_queue_;  // global_localization answers while a step waits
  ros::ServiceServer global_srv_;
  long frames_ = 0, resets_ = 0, relocalizations_ = 0, mirror_flips_ = 0;
  double last_check_score_ = std::numeric_limits<double>::quiet_NaN();
  localization::RbpfLocalizer::StepResult last_;
  double last_compute_s_ = 0.0;
  ros_conv::NodeDiagnostics
      diagnostics_;  // last: its heartbeat stops before the state it reads goes
};

}  // namespace adaptive_perception
