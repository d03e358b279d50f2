#pragma once
// A plausible RoboCup venue for the field simulator: surface materials (linear RGB albedo), the
// ceiling light rig, ambient light and the camera's exposure. `draw(seed)` gives "another
// tournament": different carpet and paint shades, lamp positions, colour temperatures and
// intensities.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "adaptive_perception/world/label_renderer.h"
#include "adaptive_perception/world/lighting.h"

namespace adaptive_perception::sim {

struct Materials {  // linear RGB albedo, 0..1
  Eigen::Vector3d carpet{0.05, 0.24, 0.06};
  Eigen::Vector3d line{0.78, 0.78, 0.76};
  Eigen::Vector3d wall{0.82, 0.82, 0.80};
  Eigen::Vector3d goal_yellow{0.80, 0.62, 0.06};
  Eigen::Vector3d goal_cyan{0.08, 0.38, 0.70};
  Eigen::Vector3d beacon_white{0.80, 0.80, 0.78};
  Eigen::Vector3d pink{0.85, 0.25, 0.45};
  Eigen::Vector3d yellow{0.80, 0.64, 0.07};
  Eigen::Vector3d cyan{0.09, 0.40, 0.72};
  Eigen::Vector3d orange{0.90, 0.30, 0.04};
  Eigen::Vector3d room{0.16, 0.13,
                       0.11};  // what lies beyond the field (spectators, walls): textured
};

struct FieldEnvironment {
  Materials materials;
  std::vector<world::LightBank> banks;  // the rig with every bank at its nominal intensity
  double ambient_intensity = 0.03;
  double ambient_color_temperature_k = 6500.0;
  double exposure =
      1.0;  // camera gain from irradiance x albedo to linear sensor value (1 = saturation)
  std::uint64_t seed = 0;

  /// The lab: four 4000 K fluorescent banks over the field; seed 0.
  static FieldEnvironment nominal();
  /// Environment number `seed` (0 gives nominal()).
  static FieldEnvironment draw(std::uint64_t seed);

  /// Albedo of the surface a ray hit.
  const Eigen::Vector3d& albedo(const world::RayHit& hit) const;
};

}  // namespace adaptive_perception::sim
