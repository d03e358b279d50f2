#pragma once
// The colour estimation pipeline with known camera poses (what the color_estimator node and the
// evaluate_color_estimation tool both run): label the pixels by rendering the field map from the camera
// pose, take the image's colour statistics, run the (switching) Kalman filter over lighting, and classify
// every pixel with the current model through the lookup table.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "adaptive_perception/color/color_lut.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/color/color_model.h"
#include "adaptive_perception/color/field_segmentation.h"
#include "adaptive_perception/color/switching_color_filter.h"
#include "adaptive_perception/world/label_renderer.h"

namespace adaptive_perception::color {

struct ColorEstimatorConfig {
  ColorModelConfig model;
  SwitchingFilterConfig switching;
  /// Rebuild the lookup table when a colour moved by this many standard deviations (ColorLutCache).
  double lut_rebuild_sigma = 0.1;
  /// Pixels within this many pixels of a label edge in the rendered map are not used for the colour
  /// statistics (pose error and the camera's motion blur make edges unreliable). 0 uses every pixel.
  int edge_margin_px = 1;
  /// Images without a camera pose are classified without one (color/field_segmentation.h: field,
  /// lines, background) instead of being dropped; images with a pose take the pose-driven update.
  bool pose_free = false;
  /// The pose-free segmentation's settings.
  FieldSegmentationConfig segmentation;
  /// A class id (0..5) whose observations are withheld from the filter (the Table 1 experiment); -1: none.
  int withheld_class = -1;
  /// The tunable fields (config/fields.h), color_estimator's parameters: the colour model's and
  /// the switching filter's numbers, edge_margin_px, lut_rebuild_sigma, pose_free and the pose-free
  /// segmentation's (FieldSegmentationConfig::fields()). The enums
  /// (observation_noise, mixing) and withheld_class (an experiment's) aside.
  static const config::Fields<ColorEstimatorConfig>& fields();
  void validate() const;
};

class ColorEstimator {
 public:
  /// Throws std::invalid_argument on a bad config or priors that do not match the model.
  ColorEstimator(const world::FieldMap& map, const world::PinholeCamera& camera,
                 const std::vector<LightingPrior>& priors, const ColorEstimatorConfig& config);

  struct Result {
    cv::Mat expected_labels;  // CV_8UC1: the map rendered from the camera pose
    cv::Mat classified;       // CV_8UC1: ML class per pixel under the updated model (255 unknown)
    ColorObservation observation;
    double log_likelihood = 0.0;  // of the image's colour means under the filter's prediction
    int active_mode = 0;
    bool time_reset = false;  // time went backwards: the filter was reset to its priors first
  };

  /// One image (CV_8UC3 YUV) taken at t_s with the camera at map_to_optical.
  Result process(double t_s, const cv::Mat& yuv, const Eigen::Isometry3d& map_to_optical);
  /// Classification only, with the current model (CV_8UC3 YUV or CV_8UC2 UYVY).
  void classify(const cv::Mat& image, cv::Mat* labels);

  void reset();
  const SwitchingColorFilter& filter() const { return filter_; }
  SwitchingColorFilter& filter() { return filter_; }
  const ColorEstimatorConfig& config() const { return config_; }
  int lutRebuilds() const { return lut_.rebuilds(); }
  const world::PinholeCamera& camera() const { return renderer_.camera(); }
  void setLutRebuildSigma(double s) { lut_.setRebuildSigma(s); }

 private:
  ColorEstimatorConfig config_;
  world::LabelRenderer renderer_;
  SwitchingColorFilter filter_;
  ColorLutCache lut_;
  std::optional<double> last_t_s_;
};

}  // namespace adaptive_perception::color
