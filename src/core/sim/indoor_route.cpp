#include "adaptive_perception/sim/indoor_route.h"

#include <algorithm>
#include <cmath>

#include "adaptive_perception/math/angles.h"

namespace adaptive_perception::sim {

IndoorRoute::IndoorRoute(const IndoorWorld& world, std::uint64_t seed, IndoorRouteConfig config)
    : world_(world), config_(config), rng_(seed) {
  const Eigen::Vector2d a = world_.route[0].xy_m, b = world_.route[1].xy_m;
  true_pose_ = math::SE2(a.x(), a.y(), std::atan2(b.y() - a.y(), b.x() - a.x()));
  odom_pose_ = math::SE2(0.0, 0.0, 0.0);
}

void IndoorRoute::move(double forward_m, double turn_rad) {
  true_pose_ = true_pose_ * math::SE2(forward_m, 0.0, turn_rad);
  // Odometry reports the motion with noise growing with its square root.
  const double nt = config_.odom_translation_noise_m_per_sqrt_m * std::sqrt(std::abs(forward_m));
  const double nr = config_.odom_rotation_noise_rad_per_sqrt_rad *
                    std::sqrt(std::abs(turn_rad) + 0.1 * std::abs(forward_m));
  // One draw per statement (an argument list's order is the compiler's), in the order the
  // simulated runs behind the figures were made in.
  const double turn_noise = rng_.gaussian(0.0, nr), side_noise = rng_.gaussian(0.0, 0.3 * nt),
               forward_noise = rng_.gaussian(0.0, nt);
  odom_pose_ = odom_pose_ * math::SE2(forward_m + forward_noise, side_noise, turn_rad + turn_noise);
}

bool IndoorRoute::step(double dt) {
  double budget = dt;  // seconds of motion left in this step
  while (budget > 1e-12 && !finished_) {
    const RouteStop& stop = world_.route[target_];
    if (arrived_) {
      if (stop.spin && spun_rad_ < 2.0 * M_PI) {
        const double turn = std::min(2.0 * M_PI - spun_rad_, world_.turn_rate_radps * budget);
        move(0.0, turn);
        spun_rad_ += turn;
        budget -= turn / world_.turn_rate_radps;
        continue;
      }
      if (target_ + 1 >= world_.route.size()) {
        finished_ = true;
        break;
      }
      ++target_;
      spun_rad_ = 0.0;
      arrived_ = false;
    }
    const Eigen::Vector2d goal = world_.route[target_].xy_m;
    const Eigen::Vector2d to = goal - Eigen::Vector2d(true_pose_.x_m, true_pose_.y_m);
    const double dist = to.norm();
    if (dist < 1e-6) {
      arrived_ = true;
      continue;
    }
    const double heading_err = math::wrapAngle(std::atan2(to.y(), to.x()) - true_pose_.yaw_rad);
    if (std::abs(heading_err) > 1e-6) {
      const double turn = std::copysign(
          std::min(std::abs(heading_err), world_.turn_rate_radps * budget), heading_err);
      move(0.0, turn);
      budget -= std::abs(turn) / world_.turn_rate_radps;
      continue;
    }
    const double fwd = std::min(dist, world_.speed_mps * budget);
    move(fwd, 0.0);
    budget -= fwd / world_.speed_mps;
    if (fwd >= dist - 1e-9) arrived_ = true;
  }
  return !finished_;
}

double IndoorRoute::duration(const IndoorWorld& world) {
  double t = 0.0, heading = 0.0;
  for (size_t k = 0; k < world.route.size(); ++k) {
    if (world.route[k].spin) t += 2.0 * M_PI / world.turn_rate_radps;
    if (k + 1 == world.route.size()) break;
    const Eigen::Vector2d d = world.route[k + 1].xy_m - world.route[k].xy_m;
    const double h = std::atan2(d.y(), d.x());
    if (k > 0) t += std::abs(math::wrapAngle(h - heading)) / world.turn_rate_radps;
    heading = h;
    t += d.norm() / world.speed_mps;
  }
  return t;
}

}  // namespace adaptive_perception::sim
