#pragma once
// The camera's image formation, with effects the estimators do not model: fixed exposure and white
// balance (so coloured light shifts colours), vignetting in luminance and chroma, gamma, saturation
// clipping, signal-dependent luminance noise and chroma noise, 4:2:2 chroma subsampling.
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/sim/field_environment.h"
#include "adaptive_perception/sim/sensor_response.h"
#include "adaptive_perception/world/label_renderer.h"

namespace adaptive_perception::sim {

struct CameraSensorConfig {
  // White point 5000 K, vignetting 0.45, gamma 2.2; the noise is the luminance's: read 1.5 levels,
  // shot 0.06 per level.
  SensorResponse sensor = {5000.0, 0.45, 2.2, 1.5, 0.06};
  double vignetting_chroma_u = 8.0;  // U shift (8-bit levels) at the corners (the ERS-7's blue)
  double chroma_noise = 2.0;         // 8-bit levels, U and V independently

  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct CameraImage {
  cv::Mat uyvy;    // CV_8UC2, what the camera delivers
  cv::Mat labels;  // CV_8UC1 true colour class per pixel (255 = background)
};

class CameraSensor {
 public:
  CameraSensor(const world::PinholeCamera& camera, CameraSensorConfig config);

  /// Forms the image of the hits (one per pixel, row-major) under `lighting`, with noise from
  /// `rng`. `map_to_optical` gives the direction of background pixels, for the room beyond the
  /// field.
  CameraImage render(const std::vector<world::RayHit>& hits,
                     const Eigen::Isometry3d& map_to_optical, const world::SceneLighting& lighting,
                     const FieldEnvironment& env, math::Rng& rng) const;

 private:
  world::PinholeCamera camera_;
  CameraSensorConfig config_;
  std::vector<float> radial2_;  // squared normalised distance from the image centre, per pixel
};

}  // namespace adaptive_perception::sim
