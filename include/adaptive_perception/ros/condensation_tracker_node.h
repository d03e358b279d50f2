#pragma once
// condensation_tracker: tracks one object by its colour distribution (papers/001 section 3):
// CONDENSATION over the target's box weighted by its colour distribution against the
// surroundings and a correlation filter (mode box, the default: the tracker that holds real
// video, tracking/box_condensation_tracker.h), the paper's CONDENSATION over the distribution
// fused with an affine snake (mode condensation), or the elliptical head tracker alone (ellipse).
//
// Its interface (parameters, subscribed and published topics, services, tf) is documented once,
// in docs/nodes/condensation_tracker.md; the parameter table there is made from parameters().
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/PolygonStamped.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include <memory>
#include <optional>

#include "adaptive_perception/SetTarget.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/ros/image_gate.h"
#include "adaptive_perception/ros/node_diagnostics.h"
#include "adaptive_perception/tracking/box_condensation_tracker.h"
#include "adaptive_perception/tracking/condensation_tracker.h"
#include "adaptive_perception/tracking/ellipse_tracker.h"

namespace adaptive_perception {

class CondensationTrackerNode {
 public:
  CondensationTrackerNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Every private parameter the node reads (its doc page's table).
  static std::vector<config::ParameterDoc> parameters();
  ~CondensationTrackerNode();

 private:
  /// processImage() through ros_conv::processGuarded: no exception ends the node.
  void onImage(const sensor_msgs::ImageConstPtr& msg);
  void processImage(const sensor_msgs::ImageConstPtr& msg);
  void onTarget(const geometry_msgs::PolygonStampedConstPtr& msg);
  bool onSetTarget(SetTarget::Request& req, SetTarget::Response& res);
  bool requestTarget(const cv::Rect2d& roi, std::string* why);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);

  enum class Mode { kBox, kCondensation, kEllipse };
  Mode mode_ = Mode::kBox;
  tracking::BoxTrackerConfig box_config_;
  std::unique_ptr<tracking::BoxCondensationTracker> box_;
  tracking::CondensationConfig config_;
  tracking::EllipseTrackerConfig ellipse_config_;
  std::uint64_t seed_ = 1;
  std::unique_ptr<tracking::CondensationTracker> tracker_;
  std::unique_ptr<tracking::EllipseTracker> ellipse_;
  std::optional<cv::Rect2d> pending_target_;  // started on the next image
  std::optional<cv::Rect2d> last_target_;     // started again when time goes backwards
  cv::Size image_size_;                       // of the last image taken (empty before the first)
  bool publish_overlay_ = true;
  ros_conv::ImageGate gate_{"condensation_tracker", 30.0};
  image_transport::Subscriber image_sub_;
  ros::Subscriber target_sub_;
  ros::Publisher object_pub_;
  image_transport::Publisher segmentation_pub_, overlay_pub_;
  ros::ServiceServer target_srv_;
  long frames_ = 0, lost_frames_ = 0, reacquired_ = 0;
  bool lost_ = false;
  double confidence_ = 0.0;
  ros_conv::NodeDiagnostics
      diagnostics_;  // last: its heartbeat stops before the state it reads goes
};

}  // namespace adaptive_perception
