#pragma once
// LaserSlam: the mapper for real laser logs and robots, one scan at a time, as ekf_slam_mapper and
// evaluate_slam run it:
//   1. the laser-odometry front end (scan_matcher.h, LaserOdometry) matches the scan against its
//      local map, with the wheel odometry as the prior;
//   2. the line-landmark EKF (line_ekf_slam.h) predicts from the front end's pose, with the front
//      end's own noise (front_end_motion), and updates with the scan's lines: the local map;
//   3. the loop closer (pose_graph.h, LoopClosingMapper) keeps a pose graph over the EKF's
//      keyframes, the front end's relative pose standing in where the EKF jumped, with loop edges
//      from scan matching; every scan's final pose is the optimised graph's. Its wide search's
//      window follows the chain's uncertainty: the EKF's prediction noise per scan, or the front
//      end's step covariance where larger (along what its scan match cannot see).
// With front_end off the EKF predicts from the wheel odometry with LineEkfSlamConfig::motion (the
// paper's filter, as the simulator's consistency checks run it); with loop_closing off the EKF's
// pose is the answer.
//
// Guarantees: add() never throws on a scan with few or no points (the front end then follows the
// wheel odometry, and the loop closer makes no match); trajectory() has one pose per add(), in
// order; pose() is trajectory().back() without building the whole trajectory.
#include <Eigen/Core>
#include <vector>

#include "adaptive_perception/localization/motion_model.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/slam/line_ekf_slam.h"
#include "adaptive_perception/slam/pose_graph.h"
#include "adaptive_perception/slam/scan_matcher.h"

namespace adaptive_perception::slam {

struct LaserSlamConfig {
  bool front_end = true;     // predict the EKF from laser odometry (else from wheel odometry)
  bool loop_closing = true;  // a pose graph with loop edges over the EKF's keyframes
  LaserOdometryConfig laser_odometry;
  // The EKF's prediction noise when the front end predicts, in MotionModelConfig's terms
  // (sd(dtheta) = alpha1 |r| + alpha2 |t| + min_r; sd(dx, dy) = alpha3 |t| + alpha4 |r| + min_t):
  // a quarter of the wheel-odometry model (LineEkfSlamConfig::motion) in every term, because the
  // front end's rotation error is 0.24-0.27 times what that model gives on the benchmark logs'
  // relations. The measurements behind it: docs/slam_real_logs.md (2026-12-03).
  localization::MotionModelConfig front_end_motion{0.025, 0.0125, 0.02, 0.0025, 0.00025, 0.00025};
  LineEkfSlamConfig ekf;
  LoopClosingConfig loop;
  /// The fields a node or tool sets (config/fields.h): front_end, loop_closing, wide_search and
  /// LineEkfSlamConfig's table.
  static const config::Fields<LaserSlamConfig>& fields();
  void validate() const;  // throws std::invalid_argument naming the bad field
};

class LaserSlam {
 public:
  explicit LaserSlam(const LaserSlamConfig& config = LaserSlamConfig(),
                     const math::SE2& start = math::SE2(),
                     const Eigen::Matrix3d& start_cov = Eigen::Matrix3d::Zero());

  struct Step {
    math::SE2 prediction;           // what the EKF predicted from (front end or wheel odometry)
    LineEkfSlam::UpdateResult ekf;  // the line update
  };
  /// An absolute position measurement for the external variant (eqs. 26-27), in map.
  struct ExternalPosition {
    Eigen::Vector2d xy_m;
    Eigen::Matrix2d cov;
  };
  /// One scan: its valid points in the robot frame (for the front end and the loop closer; may be
  /// empty), its lines as observations (toObservations), the wheel odometry pose
  /// (odom -> base_link) at its stamp, and optionally an external position at the same instant,
  /// applied after the line update and before the loop closer takes the EKF's pose.
  Step add(const std::vector<Eigen::Vector2d>& points_robot,
           const std::vector<LineObservation>& lines, const math::SE2& odom,
           const ExternalPosition* external = nullptr);

  /// The latest scan's final pose in map (the graph's when loop closing, else the EKF's).
  math::SE2 pose() const;
  /// Every scan's final pose, in the order added.
  std::vector<math::SE2> trajectory() const;
  int scans() const { return scans_; }

  LineEkfSlam& ekf() { return ekf_; }  // e.g. for an external position sensor
  const LineEkfSlam& ekf() const { return ekf_; }
  const LaserOdometry& frontEnd() const { return front_end_; }
  const LoopClosingMapper& loopCloser() const { return loop_; }
  const LaserSlamConfig& config() const { return config_; }

 private:
  static LineEkfSlamConfig ekfConfig(const LaserSlamConfig& c);
  /// c.loop with chain_noise the EKF's own prediction noise (the chain's uncertainty is the local
  /// estimator's).
  static LoopClosingConfig loopConfig(const LaserSlamConfig& c);

  LaserSlamConfig config_;
  LaserOdometry front_end_;
  LineEkfSlam ekf_;
  LoopClosingMapper loop_;
  std::vector<math::SE2> ekf_poses_;  // every scan's EKF pose, when not loop closing
  int scans_ = 0;
};

}  // namespace adaptive_perception::slam
