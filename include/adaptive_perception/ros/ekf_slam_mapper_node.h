#pragma once
// ekf_slam_mapper: line-landmark EKF SLAM (Garulli et al. 2005, section 2.2) with a laser-odometry
// front end and loop closing. The algorithm is slam::LaserSlam (slam/laser_slam.h), the same that
// evaluate_slam runs; this node feeds it line_extractor's segments, the scans they came from and
// the odometry from tf, and publishes the robot pose, map -> odom and the map.
//
// Parameters (private; defaults and ranges in config/ekf_slam_mapper.yaml):
//   ~front_end (bool, true): predict the EKF from laser odometry matched on each scan (needs
//   `scan`), with slam::LaserSlamConfig::front_end_motion as its noise; false: from the wheel
//   odometry with ~odom_alpha1.. (the paper's filter).
//   ~loop_closing (bool, true): a pose graph over the EKF's keyframes with loop edges from scan
//   matching (needs `scan`); the published pose, map -> odom, path and grid are the graph's.
//   ~wide_search (bool, true): with ~loop_closing, loops the estimate has drifted metres from are
//   searched for by branch and bound and taken once two matches agree
//   (slam::LoopClosingConfig::wide_search).
//   ~initial_map (path, default none): a line map written by ~save_map (slam/map_io.h), loaded at
//   start-up (and again on ~reset) to localize against without extending it: its confirmed and
//   fixed landmarks correct the pose with their covariance, no landmark is started, and loop
//   closing is off (the map is already global). A file that cannot be read or parsed stops the
//   node with the file and line. ~save_map never replaces it unless asked (overwrite).
//   ~variant (standard | anchor | external), ~retire_after_updates (int, 0 = off; the paper: 50),
//   ~anchor_min_angle_rad.
//   ~association (jcbb | nn), ~gate_probability, ~confirm_sightings, ~tentative_timeout_scans,
//   ~min_new_line_length_m, ~line_model_rho_std_m, ~line_model_alpha_std_rad, ~merge_landmarks,
//   ~share_landmarks, ~first_estimate_jacobians.
//   ~odom_alpha1..4, ~odom_min_translation_std_m, ~odom_min_rotation_std_rad: the wheel
//   odometry's motion noise (used with ~front_end false).
//   ~initial_pose ([x_m, y_m, yaw_rad], default the origin), ~initial_pose_std ([m, m, rad]).
//   ~external_gate_probability: external poses whose innovation fails this chi-square gate are
//   rejected (outliers).
//   ~map_frame, ~odom_frame, ~base_frame, ~publish_tf (bool), ~transform_tolerance_s,
//   ~tf_timeout_s, ~map_file (save_map's default path), ~path_max_poses.
//   ~grid_resolution_m (0.05), ~grid_max_range_m (30), ~map_update_interval_s (5; 0: no grid),
//   ~grid_keyframe_distance_m (0.1), ~grid_keyframe_angle_rad (0.1): the occupancy grid
//   (slam/occupancy_grid.h), rendered from the scans kept after that much motion, each at the
//   pose the filter gave it.
//   ~time_back_restart_s (s): an input older than the last is dropped; older by more than
//   this (or the clock jumping back) restarts (ros/stamp_order.h).
// Subscribed:
//   lines (adaptive_perception/LineSegmentArray from line_extractor, in the laser frame),
//   scan (sensor_msgs/LaserScan: the scans the lines came from, matched by stamp: the front end's
//   and the loop closer's points, and the grid's scans),
//   tf odom -> base_link and base_link -> the lines' frame at the scan stamp,
//   external_pose (geometry_msgs/PoseWithCovarianceStamped in map; variant external only: x, y,
//   and yaw too when its variance is finite and below 1e3 rad^2).
// Published:
//   ekf_slam_mapper/pose (geometry_msgs/PoseWithCovarianceStamped), tf map -> odom,
//   ekf_slam_mapper/map (visualization_msgs/MarkerArray, drawn with the loop closer's current
//   correction of the EKF's frame: confirmed segments black, anchored /
//   retired blue, tentative grey; 2-sigma bands of each landmark's offset at its midpoint; the
//   robot's 2-sigma position ellipse), ekf_slam_mapper/path (nav_msgs/Path),
//   map (nav_msgs/OccupancyGrid, latched, every ~map_update_interval_s) and map_metadata
//   (nav_msgs/MapMetaData, latched), as gmapping publishes them,
//   /diagnostics (landmarks, update time, scans, rejected inputs).
// Services:
//   ~save_map (adaptive_perception/SaveMap): the map and its covariance as YAML (slam/map_io.h),
//   and beside it the occupancy grid in map_server's format (NAME_grid.yaml + NAME_grid.pgm),
//   each written to a temporary file and renamed; refused when one exists unless overwrite.
//   dynamic_map (nav_msgs/GetMap): the occupancy grid rendered now, as gmapping serves it.
//   ~reset (std_srvs/Trigger): forgets the map and starts again from ~initial_pose.
#include <diagnostic_updater/diagnostic_updater.h>
#include <diagnostic_updater/update_functions.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <nav_msgs/GetMap.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <sensor_msgs/LaserScan.h>
#include <std_srvs/Trigger.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>
#include <deque>
#include <memory>
#include <mutex>

#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/SaveMap.h"
#include "adaptive_perception/ros/service_queue.h"
#include "adaptive_perception/ros/stamp_order.h"
#include "adaptive_perception/slam/laser_slam.h"
#include "adaptive_perception/slam/line_ekf_slam.h"
#include "adaptive_perception/slam/occupancy_grid.h"

namespace adaptive_perception {

class EkfSlamMapperNode {
 public:
  /// Throws ros_params::ParamError with a clear message on a bad parameter.
  EkfSlamMapperNode(ros::NodeHandle nh, ros::NodeHandle pnh);

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
  std::string initial_map_;                      // ~initial_map, empty: mapping
  std::vector<slam::FixedLandmark> known_map_;  // its landmarks
  std::string map_frame_, odom_frame_, base_frame_, map_file_;
  bool publish_tf_ = true;
  double transform_tolerance_s_ = 0.1, tf_timeout_s_ = 0.2, external_gate_ = 0.999;
  int path_max_poses_ = 20000;
  ros::Time last_stamp_;
  ros_conv::StampOrder stamp_order_{"ekf_slam_mapper", "lines"};
  nav_msgs::Path path_;
  slam::OccupancyGridConfig grid_config_;
  double map_update_interval_s_ = 5.0;
  std::deque<sensor_msgs::LaserScanConstPtr> recent_scans_;  // awaiting their lines
  std::deque<ros::MessageEvent<const LineSegmentArray>> waiting_lines_;  // awaiting their scans
  static constexpr size_t kMaxWaitingLines = 10;
  std::unique_ptr<slam::GridKeyframes> keyframes_;
  // Per grid keyframe: its scan's index in slam_ and the laser mount, so that the grid is drawn
  // at the loop closer's latest poses.
  std::vector<int> grid_scan_index_;
  std::vector<math::SE2> grid_mount_;
  long grid_renders_ = 0, scans_without_laser_scan_ = 0;
  double last_grid_s_ = 0.0;

  long scans_ = 0, skipped_no_tf_ = 0, bad_segments_ = 0, resets_ = 0, external_used_ = 0,
       external_rejected_ = 0, update_failures_ = 0;
  double last_update_ms_ = 0.0, max_update_ms_ = 0.0;
  double min_freq_ = 1.0, max_freq_ = 100.0;

  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  ros::Subscriber lines_sub_, external_sub_, scan_sub_;
  ros::Publisher pose_pub_, map_pub_, path_pub_, grid_pub_, grid_meta_pub_;
  ros_conv::ServiceQueue service_queue_;  // save_map, dynamic_map and the grid's timer
  ros::ServiceServer save_srv_, get_map_srv_, reset_srv_;
  ros::SteadyTimer map_timer_;
  diagnostic_updater::Updater diagnostics_;
  ros::SteadyTimer diagnostics_timer_;  // ros/diagnostics_heartbeat.h: reports with no input too
  std::unique_ptr<diagnostic_updater::FrequencyStatus> freq_;
};

}  // namespace adaptive_perception
