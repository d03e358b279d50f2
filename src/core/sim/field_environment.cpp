#include "adaptive_perception/sim/field_environment.h"

#include <algorithm>
#include <string>

#include "adaptive_perception/math/rng.h"

namespace adaptive_perception::sim {

namespace {
// Exposure that puts a white surface (albedo 0.8) at the field centre, under the full rig, at 85%
// of saturation: what a team calibrating its camera at the venue would set.
double calibratedExposure(const FieldEnvironment& env) {
  world::SceneLighting all_on{env.ambient_intensity, env.ambient_color_temperature_k, env.banks};
  const Eigen::Vector3d e = all_on.irradiance(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  return 0.85 / (0.8 * e[1]);
}
}  // namespace

FieldEnvironment FieldEnvironment::nominal() {
  FieldEnvironment env;
  int k = 0;
  for (double sx : {-1.4, 1.4}) {
    for (double sy : {-0.9, 0.9}) {
      world::LightBank b;
      b.name = "bank_" + std::to_string(k++);
      b.position_m = {sx, sy, 2.6};
      b.intensity = 0.55;
      b.color_temperature_k = 4000.0;
      env.banks.push_back(b);
    }
  }
  env.exposure = calibratedExposure(env);
  return env;
}

FieldEnvironment FieldEnvironment::draw(std::uint64_t seed) {
  FieldEnvironment env = nominal();
  env.seed = seed;
  if (seed == 0) return env;
  math::Rng rng(0x9E3779B97F4A7C15ull ^ (seed * 0xBF58476D1CE4E5B9ull));
  auto shade = [&](Eigen::Vector3d& a, double brightness_spread, double hue_spread) {
    const double k = rng.uniform(1.0 - brightness_spread, 1.0 + brightness_spread);
    for (int c = 0; c < 3; ++c)
      a[c] = std::clamp(a[c] * k * rng.uniform(1.0 - hue_spread, 1.0 + hue_spread), 0.005, 0.95);
  };
  Materials& m = env.materials;
  shade(m.carpet, 0.25, 0.12);
  shade(m.line, 0.08, 0.03);
  shade(m.wall, 0.08, 0.03);
  m.beacon_white = m.wall;
  shade(m.goal_yellow, 0.15, 0.08);
  shade(m.goal_cyan, 0.15, 0.10);
  // Beacon paint is usually the goal paint of the same venue, with some spread.
  m.yellow = m.goal_yellow;
  m.cyan = m.goal_cyan;
  shade(m.yellow, 0.05, 0.03);
  shade(m.cyan, 0.05, 0.03);
  shade(m.pink, 0.15, 0.10);
  shade(m.orange, 0.1, 0.05);
  shade(m.room, 0.4, 0.15);

  // Lamp rig: 3 to 6 banks over the field, at one height, of one lamp type (with small spread).
  static const double kTypes[] = {2900.0, 3500.0, 4000.0, 5000.0, 6000.0};
  const double type_k = kTypes[rng.uniformInt(0, 4)];
  const int n_banks = rng.uniformInt(3, 6);
  const double height = rng.uniform(2.2, 4.0);
  env.banks.clear();
  for (int i = 0; i < n_banks; ++i) {
    world::LightBank b;
    b.name = "bank_" + std::to_string(i);
    const double along = n_banks == 1 ? 0.0 : -2.0 + 4.0 * i / (n_banks - 1);
    b.position_m = {along + rng.uniform(-0.3, 0.3), rng.uniform(-1.2, 1.2),
                    height + rng.uniform(-0.2, 0.2)};
    b.intensity = rng.uniform(0.4, 0.8) * (height * height) / (2.6 * 2.6) * 4.0 / n_banks;
    b.color_temperature_k = type_k * rng.uniform(0.95, 1.05);
    env.banks.push_back(b);
  }
  env.ambient_intensity = rng.uniform(0.01, 0.1);
  env.ambient_color_temperature_k = rng.uniform(5000.0, 7500.0);
  // The team calibrates at the venue, within +-20%.
  env.exposure = calibratedExposure(env) * rng.uniform(0.8, 1.2);
  return env;
}

const Eigen::Vector3d& FieldEnvironment::albedo(const world::RayHit& hit) const {
  using world::SurfaceKind;
  switch (hit.kind) {
    case SurfaceKind::kCarpet:
      return materials.carpet;
    case SurfaceKind::kLine:
      return materials.line;
    case SurfaceKind::kWall:
      return materials.wall;
    case SurfaceKind::kGoal:
      switch (hit.color) {
        case world::kYellow:
          return materials.goal_yellow;
        case world::kCyan:
          return materials.goal_cyan;
        default:  // white posts and nets
          return materials.wall;
      }
    case SurfaceKind::kBall:
      return materials.orange;
    case SurfaceKind::kBeacon:
      switch (hit.color) {
        case world::kPink:
          return materials.pink;
        case world::kYellow:
          return materials.yellow;
        case world::kCyan:
          return materials.cyan;
        case world::kGreen:
          return materials.carpet;
        default:
          return materials.beacon_white;
      }
    default:
      return materials.room;
  }
}

}  // namespace adaptive_perception::sim
