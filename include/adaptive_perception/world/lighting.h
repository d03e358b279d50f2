#pragma once
// Scene lighting of the field: an ambient term plus ceiling light banks, each with an intensity and
// a correlated colour temperature, that can be switched on and off. This is the simulator's
// physical model; the estimators do NOT assume it (they model lighting only as a Gaussian over
// colour means).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace adaptive_perception::world {

struct LightBank {
  std::string name;
  Eigen::Vector3d position_m{0.0, 0.0, 2.5};  // in map; a bank is treated as a point source
  double intensity = 1.0;  // irradiance on a horizontal surface straight below, relative
  double color_temperature_k = 4000.0;
  bool on = true;
};

struct SceneLighting {
  double ambient_intensity = 0.1;               // uniform irradiance from the room and windows
  double ambient_color_temperature_k = 6500.0;  // daylight
  std::vector<LightBank> banks;

  /// RGB irradiance (relative, linear) on a surface at `point_m` with unit `normal`. Each bank adds
  /// intensity * (h / d)^2 * (kDiffuseFloor + (1 - kDiffuseFloor) max(0, n.l)) in its colour: the
  /// inverse-square falloff normalised at the bank's height h, with a floor that stands for the
  /// large area of a real bank (vertical surfaces are lit too, if less).
  Eigen::Vector3d irradiance(const Eigen::Vector3d& point_m, const Eigen::Vector3d& normal) const;

  /// The sources' colours (colorTemperatureRgb of the ambient light and of each bank), for a
  /// renderer that asks for the irradiance at every pixel: Planck's law costs more than the rest
  /// of a pixel. `irradiance` with them gives the same numbers as without.
  struct SourceColors {
    Eigen::Vector3d ambient;
    std::vector<Eigen::Vector3d> banks;  // one per bank, in order
  };
  SourceColors sourceColors() const;
  Eigen::Vector3d irradiance(const Eigen::Vector3d& point_m, const Eigen::Vector3d& normal,
                             const SourceColors& colors) const;

  static constexpr double kDiffuseFloor = 0.35;
};

/// Relative RGB of black-body light of temperature T seen through three narrow-band channels (610,
/// 550 and 465 nm), normalised so that `white_point_k` gives (1, 1, 1): what a camera
/// white-balanced for white_point_k records of a white surface lit by T. Planck's law, so it is
/// exact for the channel model.
Eigen::Vector3d colorTemperatureRgb(double temperature_k, double white_point_k = 5000.0);

}  // namespace adaptive_perception::world
