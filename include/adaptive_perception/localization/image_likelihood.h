#pragma once
// The image likelihood of a camera pose on the field (Schulz & Fox 2004, eqs. 9 and 16): the
// product over a grid of pixels of each pixel's colour density under the lighting estimate, given
// the colour class the map shows at that pixel from the pose.
//
// Contract:
//  - A pixel whose predicted class has no colour model (background) scores the uniform density over
//    the YUV cube, so every grid pixel contributes and a pose does not win by seeing less of the
//    field (the paper skips such pixels); or, with background_from_image, the density of the
//    image's own background colours (BackgroundDensity): a real room beyond the field is white
//    walls, windows and people, and under the uniform density a pose wins by putting a white goal
//    post over a white wall.
//  - Each modelled pixel's density is a mixture with that uniform density (outlier_probability:
//    robots, people, mislabelled edges); the sum over pixels is multiplied by `exponent`
//    (neighbouring pixels are not independent).
//  - A pixel's predicted colour is blurred over where a pose error of the configured tolerance
//    would move it (see ImageLikelihoodConfig::position_tolerance_m), using grid neighbours only,
//    so it costs no extra rays.
//  - With several lighting modes the likelihood is the mixture over the modes with their predicted
//    probabilities.
//  - Thread-safe: every method is const and keeps no state between calls.
#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/color/switching_color_filter.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/world/label_renderer.h"

namespace adaptive_perception::localization {

struct ImageLikelihoodConfig {
  int pixel_stride = 4;  // use every stride-th pixel in x and y (a regular grid)
  double outlier_probability =
      0.1;                 // weight of the uniform density in the pixel likelihood mixture
  double exponent = 0.02;  // the image log-likelihood is multiplied by this
  // Each grid pixel is scored under a mixture of the colours the pose predicts: half the colour at
  // the pixel, an eighth each the colours at the grid pixels a pose error of position_tolerance_m
  // and heading_tolerance_rad would move it to (left/right and up/down, in whole grid steps, at
  // most max_neighbourhood_cells). A pixel-exact comparison punishes a pose a few centimetres off
  // twice, where a line is predicted and where it is seen, so near the robot (a low camera, lines a
  // few decimetres away) it scores below poses that see no line at all, and the particles drift off
  // a true peak only 1-2 cm wide. The offsets follow the ground distance each pixel looks at (the
  // camera's height and tilt are the same for every particle, so they are computed once per
  // image): a near pixel moves far in the image for a small pose error, a far one hardly at all,
  // and a fixed image-space neighbourhood would either not help near or blur the range of far
  // lines. Tolerance 0: the pixel alone (the paper).
  double position_tolerance_m = 0.05;
  double heading_tolerance_rad = 0.02;
  // The same for an error of the camera's pitch, which moves the whole view up or down by about
  // fy * pitch_tolerance_rad pixels: 0 for a camera whose pitch is known (the simulator); a NAO's
  // stance changes it by about 0.01 rad from one stand to the next (docs/cameras.md).
  double pitch_tolerance_rad = 0.0;
  int max_neighbourhood_cells = 4;
  // The strides (pixel_stride, PoseSearchConfig::pixel_stride) are in pixels of an image this
  // wide (the ERS-7's). A camera of another width samples the same directions: its strides are
  // scaled with its width, and the exponent by the reference grid's pixel count over its own, so
  // that an image weighs the same at any resolution (RbpfConfig::forCamera).
  int reference_width_px = 208;
  // What a pixel the map shows as background scores: false, the uniform density over the YUV cube
  // (the simulator's room is no colour in particular); true, the density of the colours the
  // image's pose-free segmentation (color/field_segmentation.h) finds above the field's boundary,
  // rebuilt for every image (BackgroundDensity).
  bool background_from_image = false;
  // The segmentation that finds that background runs on the image shrunk to at most this width
  // (only its boundary is used, and a colour histogram does not need it to the pixel): at the NAO's
  // 640 x 480 it cost about 37 ms an image on this project's machine, more than a 30 Hz camera
  // leaves; at 320 no more than the runs' spread (a few ms), with the NAO development points
  // localized as often as at 640 (docs/field_localization.md).
  int background_width_px = 320;
  /// Its parameters' names, ranges and docs; defined in rbpf_configs.cpp.
  static const config::Fields<ImageLikelihoodConfig>& fields();
  void validate() const { fields().validate(*this); }
};

/// How many grid steps a pixel's neighbours lie left/right (du) and up/down (dv).
struct NeighbourOffset {
  std::uint8_t du = 0, dv = 0;
};

/// Every s-th pixel in x and y from s / 2, row-major; *cols is the grid's width.
std::vector<world::PixelCoord> pixelGrid(const world::PinholeCamera& camera, int s, int* cols);
/// The number of pixels pixelGrid gives for an image of w x h pixels at stride s.
double gridPixelCount(int w, int h, int s);

/// Per pixel of a `stride`-spaced grid, the grid steps that a pose error of
/// config.position_tolerance_m / heading_tolerance_rad moves it by, for a camera at
/// base_to_optical above the ground plane z = 0 of base_link.
std::vector<NeighbourOffset> neighbourOffsets(const world::PinholeCamera& camera,
                                              const std::vector<world::PixelCoord>& pixels,
                                              int stride, const Eigen::Isometry3d& base_to_optical,
                                              const ImageLikelihoodConfig& config);

/// The colours of what lies beyond the field in one image, for the pixels a pose predicts as
/// background: a histogram of the YUV colours of the pixels a mask marks, in cubes of kBinLevels
/// levels, mixed with the uniform density over the YUV cube (weight uniform_weight, so that a
/// colour the mask never saw keeps a density). With fewer than kMinPixels marked pixels it is the
/// uniform density.
class BackgroundDensity {
 public:
  static constexpr int kBinLevels = 16;
  static constexpr int kMinPixels = 500;
  /// `yuv` CV_8UC3, `mask` CV_8UC1 of its size (non-zero: background); uniform_weight in (0, 1].
  /// std::invalid_argument otherwise.
  BackgroundDensity(const cv::Mat& yuv, const cv::Mat& mask, double uniform_weight);
  /// The log density (per YUV level cubed) of a colour.
  double logDensity(const Eigen::Vector3d& yuv) const;

 private:
  std::vector<float> log_density_;  // per bin; empty: uniform
};

/// An image on a pixel grid: the grid, its colours and each pixel's neighbour offsets (for the
/// camera pose they were computed for).
struct SampledImage {
  std::vector<world::PixelCoord> pixels;  // a `cols`-wide row-major grid
  int cols = 0;
  int stride = 1;
  std::vector<Eigen::Vector3d> values;  // YUV at pixels
  std::vector<NeighbourOffset> offsets;
  // Per pixel, the log density of its colour as background (empty: the uniform density).
  std::vector<double> background_log_density;
};

class ImageLikelihood {
 public:
  /// `model` names the colour classes that have a density; config is validated
  /// (std::invalid_argument naming the field).
  ImageLikelihood(const world::FieldMap& map, const world::PinholeCamera& camera,
                  const color::ColorModelConfig& model, const ImageLikelihoodConfig& config);

  /// The grid of every stride-th pixel, without colours or offsets.
  SampledImage grid(int stride) const;
  /// Fills image->values from `yuv` (CV_8UC3 of the camera's size; std::invalid_argument
  /// otherwise), and image->background_log_density from `background` (null: the uniform density).
  void setColours(const cv::Mat& yuv, SampledImage* image,
                  const BackgroundDensity* background = nullptr) const;
  /// Fills image->offsets for a camera at base_to_optical on the robot.
  void setOffsets(const Eigen::Isometry3d& base_to_optical, SampledImage* image) const;
  /// grid + setColours + setOffsets.
  SampledImage sample(const cv::Mat& yuv, int stride, const Eigen::Isometry3d& base_to_optical,
                      const BackgroundDensity* background = nullptr) const;

  /// The tempered log-likelihood of `image` for a robot pose and lighting estimate; fills `obs`
  /// (may be null) with the colour means under that pose's labels and `used` (may be null) with the
  /// number of pixels showing a modelled colour. image.offsets must be for base_to_optical.
  double logLikelihood(const SampledImage& image, const math::SE2& pose,
                       const color::SwitchingColorFilter& lighting,
                       const Eigen::Isometry3d& base_to_optical, color::ColorObservation* obs,
                       int* used) const;

  const world::FieldMap& map() const { return renderer_.map(); }
  const world::PinholeCamera& camera() const { return renderer_.camera(); }
  const world::LabelRenderer& renderer() const { return renderer_; }
  const ImageLikelihoodConfig& config() const { return config_; }

 private:
  world::LabelRenderer renderer_;
  color::ColorModelConfig model_;
  ImageLikelihoodConfig config_;
};

}  // namespace adaptive_perception::localization
