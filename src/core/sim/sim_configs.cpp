// The field tables (config/fields.h) of the simulators' configs, as simulate_field's,
// simulate_tracking's and bench_tracker's options name them: written once, for validate(), the
// tools' --help and their range checks.
#include "adaptive_perception/sim/field_simulator.h"
#include "adaptive_perception/sim/tracking_scene.h"

namespace adaptive_perception::sim {

const config::Fields<FieldSimConfig>& FieldSimConfig::fields() {
  using C = FieldSimConfig;
  using config::aboveZero;
  using config::closed;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("duration_s", &C::duration_s, aboveZero(36000), "simulated time (s)")
          .add("rate_hz", &C::camera_rate_hz, aboveZero(120), "camera rate (Hz)")
          .add("odom_rate_hz", &C::odom_rate_hz, closed(1, 1000), "odometry rate (Hz)")
          .add("switch_period_s", &C::switch_period_s, aboveZero(36000),
               "script switching: the light changes this often (s)")
          .add("walk_speed_mps", &C::walk_speed_mps, closed(0, 2), "walking speed (m/s)")
          .add("max_turn_rate_radps", &C::max_turn_rate_radps, aboveZero(10),
               "fastest turn towards the next waypoint (rad/s)")
          .add("waypoint_x_limit_m", &C::waypoint_x_limit_m, aboveZero(100),
               "waypoints are drawn inside |x| <= this (m)")
          .add("waypoint_y_limit_m", &C::waypoint_y_limit_m, aboveZero(100),
               "... and |y| <= this (m)")
          .add("odom_translation_scale", &C::odom_translation_scale, aboveZero(10),
               "odometry's systematic scale of the distance walked")
          .add("odom_rotation_scale", &C::odom_rotation_scale, aboveZero(10),
               "odometry's systematic scale of the angle turned")
          .add("odom_translation_noise_m_per_sqrt_m", &C::odom_translation_noise_m_per_sqrt_m,
               closed(0, 10), "odometry's random translation error (m per sqrt(m) walked)")
          .add("odom_rotation_noise_rad_per_sqrt_rad", &C::odom_rotation_noise_rad_per_sqrt_rad,
               closed(0, 10), "odometry's random rotation error (rad per sqrt(rad) turned)")
          .add("pan_period_s", &C::pan_period_s, aboveZero(1000), "head pan period (s)")
          .add("tilt_period_s", &C::tilt_period_s, aboveZero(1000), "head tilt period (s)")
          .add("gait_frequency_hz", &C::gait_frequency_hz, closed(0, 100),
               "gait shake of the camera (Hz)");
  return f;
}

const config::Fields<TrackingSceneConfig>& TrackingSceneConfig::fields() {
  using C = TrackingSceneConfig;
  using config::closed;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("frames", &C::frames, closed(1, 100000), "frames in the sequence")
          .add("width", &C::width, closed(64, 4096), "image width (px)")
          .add("height", &C::height, closed(64, 4096), "image height (px)")
          .add("rate_hz", &C::rate_hz, config::aboveZero(1000), "frame rate (Hz)")
          .add("noise_sd", &C::noise_sd, closed(0, 255),
               "camera noise, grey levels (standard deviation)");
  return f;
}

}  // namespace adaptive_perception::sim
