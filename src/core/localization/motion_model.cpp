#include "adaptive_perception/localization/motion_model.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace adaptive_perception::localization {

void MotionModelConfig::validate() const {
  const double v[] = {alpha1, alpha2, alpha3, alpha4, min_translation_std_m, min_rotation_std_rad};
  const char* n[] = {
      "alpha1", "alpha2", "alpha3", "alpha4", "min_translation_std_m", "min_rotation_std_rad"};
  for (int i = 0; i < 6; ++i)
    if (!(v[i] >= 0.0 && v[i] <= 10.0))
      throw std::invalid_argument(std::string(n[i]) + " = " + std::to_string(v[i]) +
                                  " (allowed: 0..10)");
}

Eigen::Vector2d motionNoiseStd(const math::SE2& d, const MotionModelConfig& c) {
  const double t = std::hypot(d.x_m, d.y_m), r = std::fabs(d.yaw_rad);
  return {c.alpha3 * t + c.alpha4 * r + c.min_translation_std_m,
          c.alpha1 * r + c.alpha2 * t + c.min_rotation_std_rad};
}

math::SE2 sampleMotion(const math::SE2& pose, const math::SE2& d, const MotionModelConfig& c,
                       math::Rng& rng) {
  const Eigen::Vector2d sd = motionNoiseStd(d, c);
  const math::SE2 noisy(d.x_m + rng.gaussian(0.0, sd[0]), d.y_m + rng.gaussian(0.0, sd[0]),
                        d.yaw_rad + rng.gaussian(0.0, sd[1]));
  return pose * noisy;
}

}  // namespace adaptive_perception::localization
