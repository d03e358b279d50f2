#pragma once
// ekf_slam_mapper: line-landmark EKF SLAM (Garulli et al. 2005, section 2.2) with a laser-odometry
// front end and loop closing. The algorithm is slam::LaserSlam (slam/laser_slam.h), the same that
// evaluate_slam runs; this node feeds it line_extractor's segments, the scans they came from and
// the odometry from tf, and publishes the robot pose, map -> odom and the map.
//
// Its interface (parameters, subscribed and published topics, services, tf) is documented once,
// in docs/nodes/ekf_slam_mapper.md; the parameter table there is made from parameters().
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <nav_msgs/GetMap.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>
#include <deque>
#include <memory>
#include <mutex>

#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/SaveMap.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/laser/no_return.h"
#include "adaptive_perception/ros/measurement_tf.h"
#include "adaptive_perception/ros/service_queue.h"
#include "adaptive_perception/ros/stamp_order.h"
#include "adaptive_perception/slam/laser_slam.h"
#include "adaptive_perception/slam/line_ekf_slam.h"
#include "adaptive_perception/slam/occupancy_grid.h"
#include "adaptive_perception/ros/node_diagnostics.h"

namespace adaptive_perception {

class EkfSlamMapperNode {
 public:
  /// Throws ros_params::ParamError with a clear message on a bad parameter.
  EkfSlamMapperNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Every private parameter the node reads (its doc page's table).
  static std::vector<config::ParameterDoc> parameters();

 private:
  // Lines are processed with the scan they came from: lines that arrive before their scan (the
  // extractor can answer before the mapper's own copy of the scan is delivered) wait for it, and
  // go on without it once a later scan has come or kMaxWaitingLines are waiting.
  void onLines(const ros::MessageEvent<const LineSegmentArray>& event);
  void processLines(const ros::MessageEvent<const LineSegmentArray>& event);
  void onExternalPose(const geometry_msgs::PoseWithCovarianceStampedConstPtr& msg);
  void onScan(const sensor_msgs::LaserScanConstPtr& msg);
  bool onSaveMap(SaveMap::Request& req, SaveMap::Response& res);
  bool onGetMap(nav_msgs::GetMap::Request& req, nav_msgs::GetMap::Response& res);
  bool onReset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  // The grid of the keyframes so far (copied under the lock, rendered outside it); false with
  // no keyframe yet.
  bool renderGrid(nav_msgs::OccupancyGrid* out, slam::OccupancyGrid* grid = nullptr);
  void onMapTimer();
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);
  void reset(const char* why);
  void publish(const std_msgs::Header& header, const Eigen::Isometry3d& odom_to_base);
  visualization_msgs::MarkerArray mapMarkers(const std_msgs::Header& header) const;

  std::mutex mutex_;
  slam::LaserSlamConfig config_;
  math::SE2 initial_pose_;
  Eigen::Matrix3d initial_cov_ = Eigen::Matrix3d::Zero();
  std::unique_ptr<slam::LaserSlam> slam_;
  std::string initial_map_;                     // ~initial_map, empty: mapping
  std::vector<slam::FixedLandmark> known_map_;  // its landmarks
  std::string map_frame_, odom_frame_, base_frame_, map_file_;
  bool publish_tf_ = true;
  double transform_tolerance_s_ = 0.0, external_gate_ = 0.0;  // from params
  int path_max_poses_ = 0;
  ros::Time last_stamp_;
  ros_conv::StampOrder stamp_order_{"ekf_slam_mapper", "lines"};
  nav_msgs::Path path_;
  slam::OccupancyGridConfig grid_config_;
  double map_update_interval_s_ = 0.0;
  std::deque<sensor_msgs::LaserScanConstPtr> recent_scans_;              // awaiting their lines
  std::deque<ros::MessageEvent<const LineSegmentArray>> waiting_lines_;  // awaiting their scans
  static constexpr size_t kMaxWaitingLines = 10;
  std::unique_ptr<slam::GridKeyframes> keyframes_;
  // Per grid keyframe: its scan's index in slam_ and the laser mount, so that the grid is drawn
  // at the loop closer's latest poses.
  std::vector<int> grid_scan_index_;
  std::vector<math::SE2> grid_mount_;
  long grid_renders_ = 0, scans_without_laser_scan_ = 0;
  // The laser's no-return value found from its readings, for a scan whose range_max is wrong
  // (laser/no_return.h); readings at it are not walls.
  laser::NoReturnFinder no_return_;
  long no_returns_marked_ = 0;
  double last_grid_s_ = 0.0;

  long scans_ = 0, bad_segments_ = 0, resets_ = 0, external_used_ = 0,
       external_rejected_ = 0, update_failures_ = 0;
  double last_update_ms_ = 0.0, max_update_ms_ = 0.0;

  ros_conv::MeasurementTf tf_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  ros::Subscriber lines_sub_, external_sub_, scan_sub_;
  ros::Publisher pose_pub_, map_pub_, path_pub_, grid_pub_, grid_meta_pub_;
  ros_conv::ServiceQueue service_queue_;  // save_map, dynamic_map and the grid's timer
  ros::ServiceServer save_srv_, get_map_srv_, reset_srv_;
  ros::SteadyTimer map_timer_;
  ros_conv::NodeDiagnostics diagnostics_;  // last: its heartbeat stops before the state it reads goes
};

}  // namespace adaptive_perception
