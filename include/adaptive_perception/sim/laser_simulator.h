#pragma once
// 2-D laser simulator: a polygon world from YAML (config/worlds/*.yaml), a robot driving a closed
// route with noisy odometry, and a laser with beam count, field of view, range noise, max-range
// returns for misses and random dropouts. Also gives, per scan, the true wall segments in view (the
// part of each wall that returns hit) for evaluating line extraction. Deterministic for a seed.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "adaptive_perception/laser/scan.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::sim {

struct LaserSensorConfig {
  int beams = 361;
  double fov_rad = 3.14159265358979323846;  // centred on the laser's x axis
  double max_range_m = 8.0;
  double min_range_m = 0.05;
  double range_noise_std_m = 0.01;
  double dropout_probability = 0.01;  // a beam returns nothing (reported as max range)
  // The range_max the scans state (0: max_range_m; else at least max_range_m). A log that states
  // more than its laser reaches (no PARAM line: 81.9 m) has its no-returns, written as
  // max_range_m, below range_max.
  double stated_range_max_m = 0.0;
  double rate_hz = 10.0;
  math::SE2 mount{0.1, 0.0, 0.0};  // laser in base_link
};

struct LaserWorld {
  std::string name;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> walls;  // segments in map
  std::vector<Eigen::Vector2d> route;                              // closed loop of waypoints
  double speed_mps = 0.4;
  double max_turn_rate_radps = 1.0;
  double odom_translation_noise_m_per_sqrt_m = 0.02;
  double odom_rotation_noise_rad_per_sqrt_rad = 0.03;
  LaserSensorConfig laser;

  /// Loads a world (keys: name, walls: list of polylines [[x, y], ...], route: [[x, y], ...], and
  /// optional speed_mps, laser: {beams, fov_deg, max_range_m, stated_range_max_m,
  /// range_noise_std_m, dropout_probability, rate_hz}). Throws std::runtime_error naming the file,
  /// line and key on any problem.
  static LaserWorld loadYaml(const std::string& path);
};

struct VisibleWall {
  int wall = -1;
  Eigen::Vector2d start_m, end_m;  // extreme hit points along the wall, in the laser frame
  int hits = 0;
};

class LaserSimulator {
 public:
  LaserSimulator(const LaserWorld& world, std::uint64_t seed);
  /// Advances the robot by dt seconds along the route.
  void step(double dt_s);
  /// A scan from the current true pose, and the walls in view.
  laser::LaserScan2D scan(std::vector<VisibleWall>* visible);
  const math::SE2& truePose() const { return true_pose_; }
  const math::SE2& odomPose() const { return odom_pose_; }
  const LaserWorld& world() const { return world_; }

 private:
  LaserWorld world_;
  math::Rng rng_;
  math::SE2 true_pose_, odom_pose_;
  size_t target_ = 1;
};

}  // namespace adaptive_perception::sim
