#include "adaptive_perception/sim/field_simulator.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/math/angles.h"

namespace adaptive_perception::sim {

using math::kPi;

const config::EnumNames<LightingScript>& lightingScripts() {
  static const config::EnumNames<LightingScript> names("script",
                                                       {{LightingScript::kBright, "bright"},
                                                        {LightingScript::kDark, "dark"},
                                                        {LightingScript::kSwitching, "switching"},
                                                        {LightingScript::kDrift, "drift"},
                                                        {LightingScript::kKidnap, "kidnap"}});
  return names;
}

LightingScript parseLightingScript(const std::string& name) {
  return lightingScripts().parse(name);
}

void FieldSimConfig::validate() const {
  fields().validate(*this);
  sensor.validate();
}

FieldSimulator::FieldSimulator(const world::FieldMap& map, const world::PinholeCamera& camera,
                               const world::HeadChain& head, const FieldSimConfig& config)
    : map_(map),
      camera_(camera),
      head_(head),
      config_(config),
      env_(FieldEnvironment::draw(config.environment_seed)),
      renderer_(map, camera),
      sensor_(camera, config.sensor),
      motion_rng_(config.seed * 3 + 1),
      odom_rng_(config.seed * 3 + 2),
      image_rng_(config.seed * 3 + 3) {
  config_.validate();
  if (config_.kidnap_time_s < 0.0) config_.kidnap_time_s = 0.5 * config_.duration_s;
  // Start at a random free place, facing anywhere.
  state_.true_pose =
      math::SE2(motion_rng_.uniform(-config_.waypoint_x_limit_m, config_.waypoint_x_limit_m),
                motion_rng_.uniform(-config_.waypoint_y_limit_m, config_.waypoint_y_limit_m),
                motion_rng_.uniform(-kPi, kPi));
  pickWaypoint();
  advanceTo(0.0);
}

void FieldSimulator::pickWaypoint() {
  for (int tries = 0; tries < 1000; ++tries) {
    const Eigen::Vector2d w(
        motion_rng_.uniform(-config_.waypoint_x_limit_m, config_.waypoint_x_limit_m),
        motion_rng_.uniform(-config_.waypoint_y_limit_m, config_.waypoint_y_limit_m));
    const Eigen::Vector2d here(state_.true_pose.x_m, state_.true_pose.y_m);
    if ((w - here).norm() > 0.8 && map_.isFree(w.x(), w.y(), 0.2)) {
      waypoint_ = w;
      return;
    }
  }
  waypoint_ = Eigen::Vector2d::Zero();
}

void FieldSimulator::step(double dt) {
  const math::SE2& p = state_.true_pose;
  const Eigen::Vector2d to = waypoint_ - Eigen::Vector2d(p.x_m, p.y_m);
  if (to.norm() < 0.1) {
    pickWaypoint();
  }
  const double heading_err = math::angleDiff(std::atan2(to.y(), to.x()), p.yaw_rad);
  const double omega =
      std::clamp(2.0 * heading_err, -config_.max_turn_rate_radps, config_.max_turn_rate_radps);
  const double c = std::cos(heading_err);
  const double v = config_.walk_speed_mps * (c > 0.0 ? c * c : 0.0);

  // True motion in the body frame, then the same increment as legged odometry measures it.
  const math::SE2 delta(v * dt, 0.0, omega * dt);
  math::SE2 next = p * delta;
  if (!map_.isFree(next.x_m, next.y_m, 0.12)) {  // never through walls: turn on the spot instead
    next = p * math::SE2(0.0, 0.0, omega * dt);
    pickWaypoint();
  }
  const double trans = std::hypot(delta.x_m, delta.y_m);
  const double rot = std::fabs(delta.yaw_rad);
  const double t_sd = config_.odom_translation_noise_m_per_sqrt_m * std::sqrt(trans);
  const double r_sd = config_.odom_rotation_noise_rad_per_sqrt_rad * std::sqrt(rot) +
                      0.5 * config_.odom_rotation_noise_rad_per_sqrt_rad * std::sqrt(trans);
  const math::SE2 measured(
      delta.x_m * config_.odom_translation_scale + odom_rng_.gaussian(0.0, t_sd),
      delta.y_m + odom_rng_.gaussian(0.0, 0.5 * t_sd),
      delta.yaw_rad * config_.odom_rotation_scale + config_.odom_yaw_drift_rad_per_m * trans +
          odom_rng_.gaussian(0.0, r_sd));
  state_.true_pose = next;
  state_.odom_pose = state_.odom_pose * measured;
  if (v > 1e-3)
    gait_phase_ += 2.0 * kPi * config_.gait_frequency_hz * dt * (v / config_.walk_speed_mps);
}

void FieldSimulator::advanceTo(double t_s) {
  const double dt_max = 1.0 / config_.odom_rate_hz;
  while (state_.t_s < t_s - 1e-12) {
    const double dt = std::min(dt_max, t_s - state_.t_s);
    step(dt);
    state_.t_s += dt;
    if (config_.script == LightingScript::kKidnap && !state_.kidnapped &&
        state_.t_s >= config_.kidnap_time_s) {
      // Teleport: the true pose jumps, odometry knows nothing of it.
      for (int tries = 0; tries < 1000; ++tries) {
        const math::SE2 q(
            motion_rng_.uniform(-config_.waypoint_x_limit_m, config_.waypoint_x_limit_m),
            motion_rng_.uniform(-config_.waypoint_y_limit_m, config_.waypoint_y_limit_m),
            motion_rng_.uniform(-kPi, kPi));
        const double jump = std::hypot(q.x_m - state_.true_pose.x_m, q.y_m - state_.true_pose.y_m);
        if (jump > 1.5 && map_.isFree(q.x_m, q.y_m, 0.2)) {
          state_.true_pose = q;
          break;
        }
      }
      state_.kidnapped = true;
      pickWaypoint();
    }
  }
  const double t = state_.t_s;
  state_.pan_rad = config_.pan_amplitude_rad * std::sin(2.0 * kPi * t / config_.pan_period_s);
  state_.tilt_rad = config_.tilt_mean_rad +
                    config_.tilt_amplitude_rad * std::sin(2.0 * kPi * t / config_.tilt_period_s);
  state_.pan_rad = std::clamp(state_.pan_rad, head_.min_pan_rad, head_.max_pan_rad);
  state_.tilt_rad = std::clamp(state_.tilt_rad, head_.min_tilt_rad, head_.max_tilt_rad);
  state_.bob_z_m = config_.gait_bob_m * std::sin(2.0 * gait_phase_);
  state_.bob_pitch_rad = config_.gait_pitch_rad * std::sin(gait_phase_);
}

LightingSnapshot FieldSimulator::lightingAt(double t_s) const {
  LightingSnapshot snap;
  world::SceneLighting& l = snap.lighting;
  l.ambient_intensity = env_.ambient_intensity;
  l.ambient_color_temperature_k = env_.ambient_color_temperature_k;
  l.banks = env_.banks;
  snap.condition = "bright";
  auto only = [&](size_t keep) {
    for (size_t i = 0; i < l.banks.size(); ++i) l.banks[i].on = i == keep;
  };
  switch (config_.script) {
    case LightingScript::kBright:
    case LightingScript::kKidnap:
      break;
    case LightingScript::kDark:
      only(0);  // "turning off all but one light"
      snap.condition = "dark";
      break;
    case LightingScript::kSwitching: {
      // Even periods: the full rig. Odd periods: one or two banks, drawn per period (random access
      // by hashing the period index, so the pattern does not depend on how often this is called).
      const auto period = static_cast<std::uint64_t>(std::floor(t_s / config_.switch_period_s));
      if (period % 2 == 1) {
        math::Rng r((config_.seed + 1) * 0x2545F4914F6CDD1Dull + period);
        const size_t keep =
            static_cast<size_t>(r.uniformInt(0, static_cast<int>(l.banks.size()) - 1));
        only(keep);
        if (r.bernoulli(0.4)) l.banks[(keep + 1) % l.banks.size()].on = true;
        snap.condition = "dark";
      }
      break;
    }
    case LightingScript::kDrift: {
      // Over the run the banks dim to 40% and warm by 1000 K while daylight rises, then back: s
      // goes 0 -> 1 -> 0 smoothly.
      const double s = 0.5 - 0.5 * std::cos(2.0 * kPi * t_s / config_.duration_s);
      for (auto& b : l.banks) {
        b.intensity *= 1.0 - 0.6 * s;
        b.color_temperature_k = std::max(1500.0, b.color_temperature_k - 1000.0 * s);
      }
      l.ambient_intensity += 0.25 * s;
      snap.condition = "drift";
      break;
    }
  }
  for (auto& b : l.banks)
    if (!b.on) b.intensity = 0.0;
  return snap;
}

Eigen::Isometry3d FieldSimulator::trueCameraPose() const {
  return world::planarToIsometry(state_.true_pose, state_.bob_z_m, 0.0, state_.bob_pitch_rad) *
         head_.baseToOptical(state_.pan_rad, state_.tilt_rad);
}

CameraImage FieldSimulator::renderCamera() {
  const Eigen::Isometry3d pose = trueCameraPose();
  renderer_.renderHitImage(pose, &hits_);
  return sensor_.render(hits_, pose, lightingAt(state_.t_s).lighting, env_, image_rng_);
}

}  // namespace adaptive_perception::sim
