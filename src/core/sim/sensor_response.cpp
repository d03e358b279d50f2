#include "adaptive_perception/sim/sensor_response.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "adaptive_perception/config/fields.h"

namespace adaptive_perception::sim {

void SensorResponse::validate() const {
  auto check = [](bool ok, const char* name, double v, const char* range) {
    if (!ok)
      throw std::invalid_argument(std::string(name) + " = " + config::formatReal(v) +
                                  " (allowed: " + range + ")");
  };
  check(white_point_k >= 1000.0 && white_point_k <= 20000.0, "white_point_k", white_point_k,
        "[1000, 20000]");
  check(vignetting >= 0.0 && vignetting < 1.0, "vignetting", vignetting, "[0, 1)");
  check(gamma >= 0.5 && gamma <= 4.0, "gamma", gamma, "[0.5, 4]");
  check(read_noise >= 0.0, "read_noise", read_noise, ">= 0");
  check(shot_noise >= 0.0, "shot_noise", shot_noise, ">= 0");
}

double SensorResponse::level(double linear) const {
  return 255.0 * std::pow(std::clamp(linear, 0.0, 1.0), 1.0 / gamma);
}

double SensorResponse::noiseSd(double level) const {
  return std::sqrt(read_noise * read_noise + shot_noise * std::max(0.0, level));
}

}  // namespace adaptive_perception::sim
