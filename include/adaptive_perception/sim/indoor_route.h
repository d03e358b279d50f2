#pragma once
// The robot of the indoor simulator: drives an IndoorWorld's route once (turn on the spot towards
// the next stop, drive straight, turn a full circle at stops marked `spin`), with odometry that
// drifts: noise proportional to the square root of the distance driven and of the angle turned.
#include <cstdint>

#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/sim/indoor_world.h"

namespace adaptive_perception::sim {

struct IndoorRouteConfig {
  double odom_translation_noise_m_per_sqrt_m = 0.02;
  double odom_rotation_noise_rad_per_sqrt_rad = 0.03;
};

class IndoorRoute {
 public:
  IndoorRoute(const IndoorWorld& world, std::uint64_t seed, IndoorRouteConfig config = {});
  /// Advances by dt seconds; false once the route is finished (the pose stays at the end).
  bool step(double dt_s);
  bool finished() const { return finished_; }
  const math::SE2& truePose() const { return true_pose_; }
  const math::SE2& odomPose() const { return odom_pose_; }
  /// Seconds the whole route takes (computed without noise).
  static double duration(const IndoorWorld& world);

 private:
  void move(double forward_m, double turn_rad);

  const IndoorWorld& world_;
  IndoorRouteConfig config_;
  math::Rng rng_;
  math::SE2 true_pose_, odom_pose_;
  size_t target_ = 0;      // the stop being approached or spun at
  double spun_rad_ = 0.0;  // at a spin stop
  bool arrived_ = true;    // at route[target_]
  bool finished_ = false;
};

}  // namespace adaptive_perception::sim
