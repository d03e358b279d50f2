#pragma once
// A legged robot walking on the field (random waypoints, never through walls), scanning with its
// head, with noisy odometry (systematic scale/drift errors plus random noise), a gait that shakes
// the camera (not reflected in tf), and lighting that follows a script. Deterministic for (seed,
// environment_seed).
#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/sim/camera_sensor.h"
#include "adaptive_perception/sim/field_environment.h"
#include "adaptive_perception/world/camera_model.h"
#include "adaptive_perception/world/label_renderer.h"

namespace adaptive_perception::sim {

enum class LightingScript { kBright, kDark, kSwitching, kDrift, kKidnap };
/// The scripts' words: "bright", "dark", "switching", "drift", "kidnap".
const config::EnumNames<LightingScript>& lightingScripts();
LightingScript parseLightingScript(const std::string& name);

struct FieldSimConfig {
  LightingScript script = LightingScript::kBright;
  std::uint64_t seed = 1;              // robot route, odometry and image noise
  std::uint64_t environment_seed = 0;  // the venue (0 = the nominal lab)
  double duration_s = 20.0;
  double camera_rate_hz = 10.0;
  double odom_rate_hz = 30.0;

  double walk_speed_mps = 0.15;  // AIBO ERS-7 walking speed
  double max_turn_rate_radps = 0.8;
  double waypoint_x_limit_m = 2.4;  // waypoints are drawn inside |x| <= this ...
  double waypoint_y_limit_m =
      1.55;  // ... and |y| <= this: always clear of goals, beacons and walls

  // Odometry error (legged odometry is poor): systematic scale and drift, then random noise.
  double odom_translation_scale = 1.06;
  double odom_rotation_scale = 0.93;
  double odom_yaw_drift_rad_per_m = 0.04;
  double odom_translation_noise_m_per_sqrt_m = 0.02;
  double odom_rotation_noise_rad_per_sqrt_rad = 0.04;

  // Head scanning: pan and tilt (positive = nose down) as slow sinusoids.
  double pan_amplitude_rad = 1.2;
  double pan_period_s = 6.0;
  double tilt_mean_rad = 0.3;
  double tilt_amplitude_rad = 0.18;
  double tilt_period_s = 3.7;

  // Gait shake of the body while walking (applied to the true camera, not to tf).
  double gait_bob_m = 0.005;
  double gait_pitch_rad = 0.012;
  double gait_frequency_hz = 2.0;

  double switch_period_s = 4.0;  // switching: the light pattern changes this often
  double kidnap_time_s = -1.0;   // kidnap: teleport time; negative = half the duration

  CameraSensorConfig sensor;

  /// The numeric fields' names, ranges and docs (config/fields.h), as simulate_field's options
  /// name them (the seeds, the script and the sensor aside); defined in sim_configs.cpp.
  static const config::Fields<FieldSimConfig>& fields();
  void validate() const;  // throws std::invalid_argument naming the bad field and value
};

struct SimState {
  double t_s = 0.0;
  math::SE2 true_pose;  // base_link in map
  math::SE2 odom_pose;  // base_link in odom (dead reckoning)
  double pan_rad = 0.0, tilt_rad = 0.0;
  double bob_z_m = 0.0, bob_pitch_rad = 0.0;
  bool kidnapped = false;  // the teleport has happened
};

struct LightingSnapshot {
  world::SceneLighting lighting;
  std::string condition;  // "bright", "dark", "partial", "drift"
};

class FieldSimulator {
 public:
  FieldSimulator(const world::FieldMap& map, const world::PinholeCamera& camera,
                 const world::HeadChain& head, const FieldSimConfig& config);

  /// Advances the robot to t_s (seconds since the start; never backwards) in odometry-rate steps.
  void advanceTo(double t_s);
  const SimState& state() const { return state_; }
  const FieldEnvironment& environment() const { return env_; }
  const FieldSimConfig& config() const { return config_; }

  /// The lighting at time t_s (a pure function of time and seeds).
  LightingSnapshot lightingAt(double t_s) const;
  /// The true pose of camera_optical_frame in map, gait shake included.
  Eigen::Isometry3d trueCameraPose() const;
  /// Renders the camera image and true labels at the current state.
  CameraImage renderCamera();

 private:
  void step(double dt);
  void pickWaypoint();

  world::FieldMap map_;
  world::PinholeCamera camera_;
  world::HeadChain head_;
  FieldSimConfig config_;
  FieldEnvironment env_;
  world::LabelRenderer renderer_;
  CameraSensor sensor_;
  math::Rng motion_rng_, odom_rng_, image_rng_;
  SimState state_;
  Eigen::Vector2d waypoint_{0.0, 0.0};
  double gait_phase_ = 0.0;
  std::vector<world::RayHit> hits_;
};

}  // namespace adaptive_perception::sim
