#include "adaptive_perception/world/lighting.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace adaptive_perception::world {

namespace {
// Planck's law up to a constant: lambda^-5 / (exp(hc / (lambda k T)) - 1).
double planck(double wavelength_m, double temperature_k) {
  constexpr double kHcOverK = 1.438776877e-2;  // m K
  return std::pow(wavelength_m, -5.0) / std::expm1(kHcOverK / (wavelength_m * temperature_k));
}
Eigen::Vector3d channels(double t) {
  return {planck(610e-9, t), planck(550e-9, t), planck(465e-9, t)};
}
}  // namespace

Eigen::Vector3d colorTemperatureRgb(double temperature_k, double white_point_k) {
  const Eigen::Vector3d c = channels(temperature_k).cwiseQuotient(channels(white_point_k));
  return c / c[1];  // the green channel carries the intensity
}

SceneLighting::SourceColors SceneLighting::sourceColors() const {
  SourceColors c{colorTemperatureRgb(ambient_color_temperature_k), {}};
  for (const LightBank& b : banks) c.banks.push_back(colorTemperatureRgb(b.color_temperature_k));
  return c;
}

Eigen::Vector3d SceneLighting::irradiance(const Eigen::Vector3d& p,
                                          const Eigen::Vector3d& n) const {
  return irradiance(p, n, sourceColors());
}

Eigen::Vector3d SceneLighting::irradiance(const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                                          const SourceColors& colors) const {
  if (colors.banks.size() != banks.size())
    throw std::invalid_argument("SceneLighting::irradiance: colours of " +
                                std::to_string(colors.banks.size()) + " banks given for " +
                                std::to_string(banks.size()));
  Eigen::Vector3d e = ambient_intensity * colors.ambient;
  for (size_t i = 0; i < banks.size(); ++i) {
    const LightBank& b = banks[i];
    if (!b.on || b.intensity <= 0.0) continue;
    const Eigen::Vector3d to_light = b.position_m - p;
    const double d2 = std::max(to_light.squaredNorm(), 1e-6);
    const double h = b.position_m.z();
    const double cos_in = std::max(0.0, n.dot(to_light) / std::sqrt(d2));
    const double falloff = h * h / d2;
    e += b.intensity * falloff * (kDiffuseFloor + (1.0 - kDiffuseFloor) * cos_in) *
         colors.banks[i];
  }
  return e;
}

}  // namespace adaptive_perception::world
