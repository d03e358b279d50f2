#pragma once
// appearance_localizer: room classification and appearance-based Monte Carlo localization
// (papers/002) against the training frames of a place database (train_places --features, from a
// bag with ground_truth/pose).
//
// Its interface (parameters, subscribed and published topics, services, tf) is documented once,
// in docs/nodes/appearance_localizer.md; the parameter table there is made from parameters().
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <image_transport/image_transport.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/transform_broadcaster.h>

#include <functional>
#include <memory>
#include <optional>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/localization/appearance_mcl.h"
#include "adaptive_perception/localization/odometry_buffer.h"
#include "adaptive_perception/places/room_classifier.h"
#include "adaptive_perception/ros/image_gate.h"
#include "adaptive_perception/ros/node_diagnostics.h"

namespace adaptive_perception {

class AppearanceLocalizerNode {
 public:
  AppearanceLocalizerNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Every private parameter the node reads (its doc page's table).
  static std::vector<config::ParameterDoc> parameters();
  ~AppearanceLocalizerNode();

 private:
  struct Frame {  // an image the gate took
    sensor_msgs::ImageConstPtr msg;
    cv::Mat bgr;
  };
  /// processImage() through ros_conv::processGuarded: no exception ends the node.
  void onImage(const sensor_msgs::ImageConstPtr& msg);
  void processImage(const sensor_msgs::ImageConstPtr& msg);
  /// One filter step on an image the gate took, with the odometry at its stamp (or none).
  void step(const Frame& frame, const std::optional<math::SE2>& odom_pose);
  /// step() on each released image, each guarded on its own.
  void stepAll(std::vector<localization::OdometrySync<Frame>::Release> released);
  void onOdom(const nav_msgs::OdometryConstPtr& msg);
  void onInitialPose(const geometry_msgs::PoseWithCovarianceStampedConstPtr& msg);
  bool onGlobalLocalization(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);

  std::unique_ptr<places::RoomClassifier> classifier_;
  std::unique_ptr<localization::AppearanceMcl> mcl_;
  std::function<void()> make_filter_;  // (re)creates mcl_ as at start-up
  places::RoomClassifierConfig classifier_config_;
  bool use_odom_ = true, publish_tf_ = false;
  ros_conv::ImageGate gate_{"appearance_localizer", 5.0};
  std::string map_frame_, odom_frame_;
  // Each image with the odometry of its stamp (an image waits for it, at most until the next).
  localization::OdometrySync<Frame> odom_;
  std::optional<math::SE2> last_odom_;  // at the last processed image
  image_transport::Subscriber image_sub_;
  ros::Subscriber odom_sub_, initial_pose_sub_;
  double transform_tolerance_s_ = 0.0;  // from ~transform_tolerance
  long initial_poses_ = 0;
  ros::Publisher pose_pub_, particles_pub_, room_pub_;
  ros::ServiceServer global_srv_;
  tf2_ros::TransformBroadcaster tf_;
  long frames_ = 0, classified_ = 0, reinits_ = 0;
  bool stable_ = false;
  std::string last_room_;
  ros_conv::NodeDiagnostics
      diagnostics_;  // last: its heartbeat stops before the state it reads goes
};

}  // namespace adaptive_perception
