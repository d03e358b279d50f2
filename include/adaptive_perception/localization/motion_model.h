#pragma once
// Odometry motion model for a legged (omni-directional) robot, in the style of amcl's "omni" model:
// the relative motion (dx, dy, dyaw) measured by odometry between two frames, expressed in the
// earlier base frame, is perturbed by zero-mean Gaussian noise whose standard deviation grows with
// the motion:
//   sd(dx) = sd(dy) = alpha3 |t| + alpha4 |r| + min_translation_std_m
//   sd(dyaw)        = alpha1 |r| + alpha2 |t| + min_rotation_std_rad
// with t = |(dx, dy)| in metres and r = |dyaw| in radians; then composed onto the particle's pose.
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::localization {

struct MotionModelConfig {
  double alpha1 = 0.2;                   // rotation noise per radian of rotation
  double alpha2 = 0.2;                   // rotation noise (rad) per metre of translation
  double alpha3 = 0.2;                   // translation noise per metre of translation
  double alpha4 = 0.05;                  // translation noise (m) per radian of rotation
  double min_translation_std_m = 0.005;  // per step, so that particles never collapse when standing
  double min_rotation_std_rad = 0.005;
  /// As ~odom_alpha1.., ~odom_min_*; defined in rbpf_configs.cpp.
  static const config::Fields<MotionModelConfig>& fields();
  void validate() const { fields().validate(*this); }
};

/// Standard deviations (translation, rotation) of the noise for a measured relative motion.
Eigen::Vector2d motionNoiseStd(const math::SE2& odom_delta, const MotionModelConfig& config);
/// A sample of the new pose: pose * perturbed(odom_delta).
math::SE2 sampleMotion(const math::SE2& pose, const math::SE2& odom_delta,
                       const MotionModelConfig& config, math::Rng& rng);

}  // namespace adaptive_perception::localization
