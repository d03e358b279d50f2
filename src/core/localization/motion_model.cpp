#include "adaptive_perception/localization/motion_model.h"

#include <cmath>

namespace adaptive_perception::localization {

Eigen::Vector2d motionNoiseStd(const math::SE2& d, const MotionModelConfig& c) {
  const double t = std::hypot(d.x_m, d.y_m), r = std::fabs(d.yaw_rad);
  return {c.alpha3 * t + c.alpha4 * r + c.min_translation_std_m,
          c.alpha1 * r + c.alpha2 * t + c.min_rotation_std_rad};
}

math::SE2 sampleMotion(const math::SE2& pose, const math::SE2& d, const MotionModelConfig& c,
                       math::Rng& rng) {
  const Eigen::Vector2d sd = motionNoiseStd(d, c);
  // One draw per statement: an argument list's order is the compiler's.
  const double dyaw = rng.gaussian(0.0, sd[1]), dy = rng.gaussian(0.0, sd[0]),
               dx = rng.gaussian(0.0, sd[0]);
  const math::SE2 noisy(d.x_m + dx, d.y_m + dy, d.yaw_rad + dyaw);
  return pose * noisy;
}

}  // namespace adaptive_perception::localization
