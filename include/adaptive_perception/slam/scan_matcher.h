#pragma once
// Scan-to-map matching for a laser-odometry front end: a scan's points are placed where they best
// overlap a likelihood field built from earlier scans (Olson, "Real-time correlative scan
// matching", ICRA 2009: an exhaustive search over a window of poses, then a local refinement).
//
// The likelihood field: the map points rasterised at resolution_m, each cell's value
// exp(-d^2 / (2 hit_std_m^2)) with d its distance to the nearest map point (exact, and 0 beyond
// 4 hit_std_m, where it would be below 3e-4), read with bilinear interpolation. A pose's score is the mean
// field value over the scan's points (1: every point on a map point; 0: none near one).
//
// The search: yaw over [-search_yaw_rad, +search_yaw_rad] around the prior in steps of
// yaw_step_rad, and for each yaw every translation of whole cells within search_xy_m; then the
// best pose is refined by a coordinate search on the interpolated field, halving its steps down to
// a hundredth of a cell and of a yaw step. Both maximise the score minus a small pull towards the
// prior (prior_penalty).
#include <Eigen/Core>
#include <deque>
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::slam {

struct ScanMatcherConfig {
  double resolution_m = 0.05;      // field cell size
  double hit_std_m = 0.1;          // field width around each map point
  double search_xy_m = 0.3;        // translation window half-width around the prior
  double search_yaw_rad = 0.2;     // rotation window half-width (about 11.5 degrees)
  double yaw_step_rad = 0.01;      // coarse rotation step
  // The prior's pull: a pose's score loses prior_penalty * ((dx^2 + dy^2) / search_xy_m^2 +
  // dyaw^2 / search_yaw_rad^2) for its distance from the prior, so that along a direction the
  // scan cannot see (a straight corridor) the match keeps the odometry's motion instead of the
  // first of many equal scores.
  double prior_penalty = 0.05;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

class LikelihoodField {
 public:
  /// The field of `points_m` (map frame) over their bounding box plus `margin_m`. Consecutive
  /// points closer than `connect_gap_m` are joined by a line (a scan's returns along one wall), so
  /// that the field is as high between a wall's samples as on them and a match along a wall is not
  /// drawn to the samples' own spacing. Throws std::invalid_argument on no point or a box larger
  /// than 4096 x 4096 cells.
  LikelihoodField(const std::vector<Eigen::Vector2d>& points_m, double resolution_m,
                  double hit_std_m, double margin_m, double connect_gap_m = 0.0);
  /// Bilinear value at a map point; 0 outside the field.
  double at(const Eigen::Vector2d& p_m) const;
  /// The mean of at() over `points_robot` placed at `pose`.
  double score(const std::vector<Eigen::Vector2d>& points_robot, const math::SE2& pose) const;

  double resolution() const { return resolution_m_; }
  const cv::Mat& values() const { return field_; }  // CV_32F, row = y, col = x
  Eigen::Vector2d origin() const { return origin_m_; }  // the map point of cell (0, 0)'s centre

 private:
  cv::Mat field_;
  Eigen::Vector2d origin_m_;
  double resolution_m_;
};

struct ScanMatch {
  math::SE2 pose;
  double score = 0.0;  // LikelihoodField::score at pose (without the prior's pull)
};

/// The best pose of `points_robot` (robot frame) within the window around `prior`.
ScanMatch matchScan(const LikelihoodField& field, const std::vector<Eigen::Vector2d>& points_robot,
                    const math::SE2& prior, const ScanMatcherConfig& config);

/// The information (inverse covariance) of a match: the number of points times the negative
/// Hessian of the mean score at the pose (central differences on the interpolated field), its
/// negative eigenvalues set to 0. Each point counts as one measurement of a wall with the
/// field's width as its noise; along a direction the scan cannot see (a straight corridor) the
/// information is about 0.
Eigen::Matrix3d matchInformation(const LikelihoodField& field,
                                 const std::vector<Eigen::Vector2d>& points_robot,
                                 const math::SE2& pose);

/// The information of a match from the scan's geometry (the degeneracy analysis of
/// point-to-line matching): a point whose neighbours in the scan (consecutive points within
/// `wall_gap_m` of each other and of it, however many, at least two) lie on a line measures its
/// distance to that wall along the line's normal n; a return with fewer neighbours (a wall sampled
/// sparser than wall_gap_m, at a grazing angle or far away) or none on a line (a corner, clutter)
/// nothing, so that the information is a lower bound; non-finite points are skipped. Each
/// measurement has the field's width `hit_std_m` as its noise and counts by the field's value at
/// the point (a point the map does not explain tells nothing); its Jacobian row in (x, y, yaw) is
/// [n^T, n . d(R p)/dyaw]. So a round hall's walls, whose normals all pass through its centre, say
/// nothing about a turn about that centre, and a bare corridor's nothing about the motion along
/// it: exactly 0 there, where matchInformation's Hessian of the rasterised field measures its
/// bumps. `points_robot` in scan order (the beams'), at `pose`.
Eigen::Matrix3d geometricMatchInformation(const LikelihoodField& field,
                                          const std::vector<Eigen::Vector2d>& points_robot,
                                          const math::SE2& pose, double hit_std_m,
                                          double wall_gap_m);

/// Laser odometry: each scan matched against a local map of the last keyframes, the wheel
/// odometry's increment as the prior. The match and the prior are fused by their information
/// (geometricMatchInformation H; the odometry's P^-1 from odom_std_m + odom_std_per_m * distance and
/// odom_std_rad + odom_std_per_rad * turn) along the directions v of the generalised
/// eigenproblem H v = lambda P^-1 v (lambda: the scan's information along v in units of the
/// odometry's). A direction with lambda below min_match_information is degenerate (rotation in a
/// round hall, the motion along a bare corridor): there the pose keeps the prior's value, whatever
/// the match says. Along the others the two are fused unless they disagree there beyond
/// odometry_gate_chi2: then the match alone along them when it scores at least
/// odometry_gate_min_score, else the odometry alone. A scan becomes a keyframe (and the field is rebuilt) once the robot has moved
/// keyframe_translation_m or turned keyframe_rotation_rad from the last one. A match scoring
/// below min_score is not trusted: the pose follows the wheel odometry. When the odometry's
/// increment differs from the last one by more than the matcher's window (a stalled or jumping
/// odometry), the match is also tried from the last increment and from no motion, and the best
/// score wins.
struct LaserOdometryConfig {
  ScanMatcherConfig matcher;
  double max_range_m = 25.0;           // farther points are left out (sparse, and long-range
                                       // returns carry the most angular error)
  double keyframe_translation_m = 0.2;
  double keyframe_rotation_rad = 0.1;
  int local_map_keyframes = 20;        // keyframes in the local map, >= 1
  double min_score = 0.25;             // 0..1
  int min_points = 20;                 // fewer valid points: follow the wheel odometry
  // For a sensor that reaches less far than max_range_m (the farthest return seen so far), the
  // points within this of its reach are left out of the match but kept for the map: a wall newly
  // seen at the edge of the reach lies beyond the local map, and along a corridor with nothing
  // else to hold the match, matching it pulls the scan backwards, so that the corridor shrinks
  // (3.6% along the simulated loop's first corridor with its 8 m laser; 1.2% with the margin).
  double edge_margin_m = 1.0;
  double connect_gap_m = 0.3;          // consecutive returns closer than this make one wall
  double odom_std_m = 0.02;            // the wheel odometry's error per step: a floor
  double odom_std_per_m = 0.1;         // plus this share of the distance
  double odom_std_rad = 0.01;          // and in rotation
  double odom_std_per_rad = 0.1;
  // A direction the match constrains with less than this many times the odometry's information
  // (generalised eigenvalue of the match's information against the odometry's) is degenerate:
  // along it the scan tells less than the odometry, and a match's value there is arbitrary
  // (anywhere in the search window), so the pose keeps the odometry's; 0 finds no direction
  // degenerate. 0.25: the scan knows the direction at least half as well as the odometry (std at
  // most twice the odometry's). The free directions of the synthetic round hall and bare corridor
  // stay below 0.06, a furnished room's weakest at 0.62 or more (docs/slam_real_logs.md).
  double min_match_information = 0.25;
  // A match that disagrees with the odometry's increment by more than this chi-square (3 dof;
  // 16.27 is the 99.9% quantile) under both their covariances, measured along the
  // well-constrained directions only, is taken alone there: the odometry slipped, stalled or
  // jumped.
  double odometry_gate_chi2 = 16.27;
  // ... but only a match that explains the scan is believed over the odometry: below this score
  // (a new room, a crowd, half the scan beyond the local map) the disagreement is the match's
  // fault and the pose follows the odometry. In mit-csail's stall the matches that overruled
  // the odometry scored 0.94-0.98; fr-clinic's false 8-degree turns at 559-561 s scored 0.35-0.50.
  double odometry_gate_min_score = 0.7;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

class LaserOdometry {
 public:
  explicit LaserOdometry(LaserOdometryConfig config = {});
  /// The next scan: its points in the robot frame and the wheel odometry pose at its stamp.
  /// Returns the robot's matched pose, starting from the first scan's wheel odometry pose (so that
  /// it can stand in for the wheel odometry).
  math::SE2 add(const std::vector<Eigen::Vector2d>& points_robot, const math::SE2& odom);
  void reset();
  /// Of the last add(): the match score, and whether the match was taken (else odometry).
  double lastScore() const { return last_score_; }
  bool lastMatched() const { return last_matched_; }
  long matched() const { return matched_; }
  /// Matched scans whose odometry increment was left out (odometry_gate_chi2).
  long odometryRejected() const { return odometry_rejected_; }
  /// Matches that disagreed with the odometry but scored below odometry_gate_min_score, so the
  /// odometry was kept.
  long weakMatchesRejected() const { return weak_rejected_; }
  long scans() const { return scans_; }
  /// Of the last add(): the information (inverse covariance) of its step, the pose's (x, y in the
  /// frame of the returned poses, yaw) given the previous pose: along the well-constrained
  /// directions the match's (plus the odometry's when fused), along the others and when the
  /// pose followed the odometry the odometry's. Positive definite when min_match_information > 0;
  /// zero after the first scan.
  const Eigen::Matrix3d& lastInformation() const { return last_information_; }
  /// Of the last add(): how many of the 3 directions the match constrained less than
  /// min_match_information times the odometry (they kept the odometry's value); 0 when no match
  /// was made.
  int lastDegenerateDirections() const { return last_degenerate_; }

 private:
  void rebuildField();
  Eigen::Vector3d odometryStd(const math::SE2& step) const;  // (x, y, yaw) of an increment
  void setOdometryInformation(const math::SE2& step);

  LaserOdometryConfig config_;
  struct Keyframe {
    math::SE2 pose;
    std::vector<Eigen::Vector2d> points_robot;
  };
  std::deque<Keyframe> keyframes_;
  std::vector<LikelihoodField> field_;  // zero or one
  bool started_ = false;
  math::SE2 pose_, last_odom_;
  math::SE2 last_step_;  // the last scan's increment of pose_
  double farthest_seen_m_ = 0.0;  // the farthest finite return so far: the sensor's reach
  double last_score_ = 0.0;
  bool last_matched_ = false;
  int last_degenerate_ = 0;
  Eigen::Matrix3d last_information_ = Eigen::Matrix3d::Zero();
  long matched_ = 0, scans_ = 0, odometry_rejected_ = 0, weak_rejected_ = 0;
};

}  // namespace adaptive_perception::slam
