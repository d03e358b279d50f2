#include "adaptive_perception/sim/laser_simulator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "adaptive_perception/io/yaml_file.h"
#include "adaptive_perception/math/angles.h"

namespace adaptive_perception::sim {

LaserWorld LaserWorld::loadYaml(const std::string& path) {
  const YAML::Node root = io::loadYamlFile(path, "world file");
  LaserWorld w;
  auto point = [&](const YAML::Node& n) {
    const auto v = n.as<std::vector<double>>();
    if (v.size() != 2)
      throw std::runtime_error(path + ":" + std::to_string(n.Mark().line + 1) +
                               ": a point is [x, y]");
    return Eigen::Vector2d(v[0], v[1]);
  };
  try {
    w.name = root["name"] ? root["name"].as<std::string>() : path;
    if (!root["walls"] || !root["route"])
      throw std::runtime_error(path + ": needs `walls` and `route`");
    for (const auto& poly : root["walls"]) {
      std::vector<Eigen::Vector2d> pts;
      for (const auto& p : poly) pts.push_back(point(p));
      if (pts.size() < 2)
        throw std::runtime_error(path + ":" + std::to_string(poly.Mark().line + 1) +
                                 ": a wall polyline needs two points");
      for (size_t k = 0; k + 1 < pts.size(); ++k) w.walls.push_back({pts[k], pts[k + 1]});
    }
    for (const auto& p : root["route"]) w.route.push_back(point(p));
    if (w.route.size() < 2) throw std::runtime_error(path + ": the route needs two waypoints");
    if (root["speed_mps"]) w.speed_mps = root["speed_mps"].as<double>();
    if (const auto l = root["laser"]) {
      if (l["beams"]) w.laser.beams = l["beams"].as<int>();
      if (l["fov_deg"]) w.laser.fov_rad = l["fov_deg"].as<double>() * math::kPi / 180.0;
      if (l["max_range_m"]) w.laser.max_range_m = l["max_range_m"].as<double>();
      if (l["stated_range_max_m"])
        w.laser.stated_range_max_m = l["stated_range_max_m"].as<double>();
      if (l["range_noise_std_m"]) w.laser.range_noise_std_m = l["range_noise_std_m"].as<double>();
      if (l["dropout_probability"])
        w.laser.dropout_probability = l["dropout_probability"].as<double>();
      if (l["rate_hz"]) w.laser.rate_hz = l["rate_hz"].as<double>();
    }
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(path + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  if (w.laser.beams < 2 || w.laser.beams > 100000)
    throw std::runtime_error(path + ": laser.beams must be 2..100000");
  if (!(w.laser.fov_rad > 0.0 && w.laser.fov_rad <= 2 * math::kPi))
    throw std::runtime_error(path + ": laser.fov_deg must be in (0, 360]");
  if (!(w.laser.max_range_m > 0.0))
    throw std::runtime_error(path + ": laser.max_range_m must be > 0");
  if (!(w.laser.stated_range_max_m == 0.0 ||
        (std::isfinite(w.laser.stated_range_max_m) &&
         w.laser.stated_range_max_m >= w.laser.max_range_m)))
    throw std::runtime_error(path + ": laser.stated_range_max_m must be 0 or at least max_range_m");
  if (!(w.laser.rate_hz > 0.0)) throw std::runtime_error(path + ": laser.rate_hz must be > 0");
  if (!(w.speed_mps >= 0.0)) throw std::runtime_error(path + ": speed_mps must be >= 0");
  return w;
}

LaserSimulator::LaserSimulator(const LaserWorld& world, std::uint64_t seed)
    : world_(world), rng_(seed * 7 + 3) {
  const Eigen::Vector2d d = world_.route[1] - world_.route[0];
  true_pose_ = math::SE2(world_.route[0].x(), world_.route[0].y(), std::atan2(d.y(), d.x()));
}

void LaserSimulator::step(double dt) {
  const Eigen::Vector2d to =
      world_.route[target_] - Eigen::Vector2d(true_pose_.x_m, true_pose_.y_m);
  if (to.norm() < 0.15) target_ = (target_ + 1) % world_.route.size();
  const double err = math::angleDiff(std::atan2(to.y(), to.x()), true_pose_.yaw_rad);
  const double w = std::clamp(2.0 * err, -world_.max_turn_rate_radps, world_.max_turn_rate_radps);
  const double c = std::cos(err);
  const double v = world_.speed_mps * (c > 0 ? c * c : 0.0);
  const math::SE2 delta(v * dt, 0.0, w * dt);
  true_pose_ = true_pose_ * delta;
  const double ts = world_.odom_translation_noise_m_per_sqrt_m * std::sqrt(std::fabs(delta.x_m));
  const double rs = world_.odom_rotation_noise_rad_per_sqrt_rad *
                    std::sqrt(std::fabs(delta.yaw_rad) + 0.1 * std::fabs(delta.x_m));
  // One draw per statement (an argument list's order is the compiler's), in the order the
  // simulated logs behind the figures were made in.
  const double yaw_noise = rng_.gaussian(0, rs), y_noise = rng_.gaussian(0, 0.3 * ts),
               x_noise = rng_.gaussian(0, ts);
  odom_pose_ = odom_pose_ * math::SE2(delta.x_m + x_noise, y_noise, delta.yaw_rad + yaw_noise);
}

laser::LaserScan2D LaserSimulator::scan(std::vector<VisibleWall>* visible) {
  const LaserSensorConfig& L = world_.laser;
  laser::LaserScan2D s;
  s.angle_min_rad = -L.fov_rad / 2;
  s.angle_increment_rad = L.fov_rad / (L.beams - 1);
  s.range_min_m = L.min_range_m;
  s.range_max_m = L.stated_range_max_m > 0.0 ? L.stated_range_max_m : L.max_range_m;
  const math::SE2 laser_pose = true_pose_ * L.mount;
  const math::SE2 map_to_laser = laser_pose.inverse();
  const Eigen::Vector2d o(laser_pose.x_m, laser_pose.y_m);
  // Walls in view: runs of consecutive beams returning from the same wall (an occluded wall seen in
  // two places gives two pieces), each with the extreme hit points along the wall.
  struct Run {
    int wall = -1, hits = 0;
    double umin = 0, umax = 0;
  };
  std::vector<Run> runs;
  Run cur;
  auto close = [&]() {
    if (cur.wall >= 0) runs.push_back(cur);
    cur = Run();
  };
  for (int i = 0; i < L.beams; ++i) {
    const double b = laser_pose.yaw_rad + s.bearing(i);
    const Eigen::Vector2d d(std::cos(b), std::sin(b));
    double best = std::numeric_limits<double>::infinity();
    int best_wall = -1;
    double best_u = 0.0;
    for (size_t k = 0; k < world_.walls.size(); ++k) {
      const Eigen::Vector2d a = world_.walls[k].first, e = world_.walls[k].second - a;
      const double den = d.x() * e.y() - d.y() * e.x();
      if (std::fabs(den) < 1e-12) continue;
      const Eigen::Vector2d q = a - o;
      const double t = (q.x() * e.y() - q.y() * e.x()) / den,
                   u = (q.x() * d.y() - q.y() * d.x()) / den;
      if (t > 1e-9 && u >= 0.0 && u <= 1.0 && t < best) {
        best = t;
        best_wall = static_cast<int>(k);
        best_u = u;
      }
    }
    double r = L.max_range_m;
    const bool in_range = best_wall >= 0 && best < L.max_range_m;
    if (in_range && !rng_.bernoulli(L.dropout_probability)) {
      r = std::min(best + rng_.gaussian(0.0, L.range_noise_std_m), L.max_range_m - 1e-3);
      if (cur.wall != best_wall) {
        close();
        cur.wall = best_wall;
        cur.umin = cur.umax = best_u;
      }
      ++cur.hits;
      cur.umin = std::min(cur.umin, best_u);
      cur.umax = std::max(cur.umax, best_u);
    } else if (!in_range || cur.wall != best_wall) {
      close();  // a dropout on the same wall does not end its run
    }
    s.ranges_m.push_back(static_cast<float>(r));
  }
  close();
  if (visible) {
    visible->clear();
    for (const Run& run : runs) {
      const Eigen::Vector2d a = world_.walls[run.wall].first, e = world_.walls[run.wall].second - a;
      VisibleWall v;
      v.wall = run.wall;
      v.hits = run.hits;
      v.start_m = map_to_laser.transformPoint(a + run.umin * e);
      v.end_m = map_to_laser.transformPoint(a + run.umax * e);
      visible->push_back(v);
    }
  }
  return s;
}

}  // namespace adaptive_perception::sim
