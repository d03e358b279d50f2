#pragma once
// Renders camera images of an IndoorWorld by casting one ray per pixel: textured walls, floors,
// ceilings with lamp panels, furniture boxes, windows showing the view outside, sky over the
// outdoor places, and sun patches cast through the windows (a shadow ray to the sun). Lighting
// is one of three conditions, varied per run from the seed:
//   night   only the ceiling lamps (each place's own colour temperature) and street lights outside;
//   cloudy  diffuse daylight through the windows and outdoors, plus the lamps;
//   sunny   bright skylight, warm direct sun with shadows and patches through windows, the lamps.
// The camera adds what place recognition does not model: auto-exposure (as the paper's robot
// had), a white balance fixed for 5000 K (so lamp and daylight colours shift the image),
// vignetting, signal-dependent noise, gamma and 8-bit clipping. Output: bgr8.
//
// Cameras: perspective (default 309 x 240, 62 deg wide, 1 m above the floor, pitched 5 deg down)
// or omni-directional (a catadioptric "donut": an image ring between two radii maps linearly to
// elevation, azimuth around the centre with the robot's forward direction up; a black border
// outside the ring and a near-black dead centre inside it (the mirror mount), as in the paper's
// Fig. 4).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/sim/indoor_world.h"
#include "adaptive_perception/sim/sensor_response.h"

namespace adaptive_perception::sim {

enum class IndoorLightingKind { kNight, kCloudy, kSunny };
/// The lightings' words: "night", "cloudy", "sunny".
const config::EnumNames<IndoorLightingKind>& indoorLightings();
IndoorLightingKind parseIndoorLighting(const std::string& name);
std::string indoorLightingName(IndoorLightingKind kind);

/// One run's light, drawn by sample() around the condition's nominal values.
struct IndoorLighting {
  IndoorLightingKind kind = IndoorLightingKind::kCloudy;
  double lamp_scale = 1.0;  // multiplies every place's lamp intensity
  double lamp_temperature_shift_k = 0.0;
  double daylight = 1.0;  // diffuse sky light (0 at night)
  double sky_temperature_k = 6500.0;
  double sun = 0.0;  // direct sun (sunny only)
  double sun_temperature_k = 5000.0;
  Eigen::Vector3d sun_direction{0.5, 0.5, 0.7};  // unit, towards the sun, map frame
  double street_light = 0.0;                     // outdoors at night

  static IndoorLighting sample(IndoorLightingKind kind, math::Rng& rng);
};

struct IndoorCameraConfig {
  bool omni = false;
  // Perspective camera.
  int width_px = 309, height_px = 240;
  double hfov_deg = 62.0;
  double pitch_down_deg = 5.0;
  // Omni-directional camera.
  int omni_width_px = 320, omni_height_px = 240;
  double inner_radius_px = 28.0, outer_radius_px = 112.0;
  double min_elevation_deg = -55.0, max_elevation_deg = 25.0;  // at the inner / outer radius
  // Both.
  double height_m = 1.0;          // optical centre above the floor
  double exposure_target = 0.18;  // auto-exposure: mean linear luminance of the image
  double exposure_jitter = 0.08;  // relative, per image
  SensorResponse sensor;  // white balance, vignetting, gamma, noise (in each RGB channel)

  int width() const { return omni ? omni_width_px : width_px; }
  int height() const { return omni ? omni_height_px : height_px; }
  void validate() const;  // throws std::invalid_argument naming the bad field
};

class IndoorRenderer {
 public:
  IndoorRenderer(IndoorWorld world, IndoorCameraConfig camera);

  /// The bgr8 image seen from the robot at `pose` (map -> base_link), noise from `rng`.
  cv::Mat render(const math::SE2& pose, const IndoorLighting& lighting, math::Rng& rng) const;
  /// Noise-free linear radiance (RGB) along one ray, for tests.
  Eigen::Vector3d radiance(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                           const IndoorLighting& lighting) const;
  const IndoorWorld& world() const { return world_; }
  const IndoorCameraConfig& camera() const { return camera_; }
  /// True when a point sees the sun (no wall, box or ceiling in the way; windows let it through).
  bool sunVisible(const Eigen::Vector3d& point, const IndoorLighting& lighting) const;

 private:
  struct Hit;
  // One lighting and the colours of its sources (world::colorTemperatureRgb: Planck's law, the
  // costliest part of a pixel when evaluated per pixel), made once per image.
  struct Sources {
    const IndoorLighting& lighting;
    Eigen::Vector3d sky, sun, street;
    std::vector<Eigen::Vector3d> lamp;  // per place
  };
  Sources sources(const IndoorLighting& l) const;
  bool castRay(const Eigen::Vector3d& o, const Eigen::Vector3d& d, Hit* hit) const;
  Eigen::Vector3d radiance(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                           const Sources& src) const;
  Eigen::Vector3d irradiance(const Eigen::Vector3d& p, const Eigen::Vector3d& n, int place,
                             double lamp_factor, const Sources& src) const;
  Eigen::Vector3d skyRadiance(const Eigen::Vector3d& d, const Sources& src) const;
  Eigen::Vector3d wallAlbedo(int wall, int side_place, double s_m, double z_m) const;
  Eigen::Vector3d floorAlbedo(int place, double x_m, double y_m) const;

  IndoorWorld world_;
  IndoorCameraConfig camera_;
  std::vector<Eigen::Vector3d> rays_body_;  // per pixel, base_link axes (x forward, z up)
  std::vector<float> vignette_;             // per pixel gain
  std::vector<unsigned char> valid_;        // omni: 1 inside the ring, 2 dead centre, 0 border
  std::vector<double> window_light_;        // per place, daylight share through its windows
};

}  // namespace adaptive_perception::sim
