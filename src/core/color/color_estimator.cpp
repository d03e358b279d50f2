#include "adaptive_perception/color/color_estimator.h"

#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace adaptive_perception::color {

const config::Fields<ColorEstimatorConfig>& ColorEstimatorConfig::fields() {
  using C = ColorEstimatorConfig;
  using config::closed;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("drift_std_per_sqrt_s", &C::model, &ColorModelConfig::drift_std_per_sqrt_s,
               closed(0, 100), "lighting drift R (eq. 6) (8-bit levels per sqrt(s))")
          .add("observation_noise_floor_var", &C::model,
               &ColorModelConfig::observation_noise_floor_var, closed(0, 1e4),
               "pixel_over_count: added to the variance of an image's colour mean (levels^2)")
          .add("min_pixels_per_color", &C::model, &ColorModelConfig::min_pixels_per_color,
               closed(1, 1000000), "a colour enters the update only with this many labelled pixels")
          .add("unknown_mahalanobis", &C::model, &ColorModelConfig::unknown_mahalanobis,
               closed(0.5, 1e9),
               "pixels farther (Mahalanobis) than this from every colour are unknown (255)")
          .add("mode_stay_probability", &C::switching,
               &SwitchingFilterConfig::mode_stay_probability, closed(1e-3, 1),
               "probability that the lighting stays in its mode from one image to the next")
          .add("imm_prior_pull_per_s", &C::switching, &SwitchingFilterConfig::imm_prior_pull_per_s,
               closed(0, 100), "mixing imm: pull of each mode towards its prior mean (1/s)")
          .add("edge_margin_px", &C::edge_margin_px, closed(0, 20),
               "pixels this close to a label edge of the rendered map are left out (px)")
          .add("lut_rebuild_sigma", &C::lut_rebuild_sigma, closed(0, 5),
               "rebuild the YUV lookup table when a colour mean moved this many standard "
               "deviations")
          .add("pose_free", &C::pose_free,
               "classify images without a camera pose in tf without one (field, lines, "
               "background) instead of dropping them")
          .nest(&C::segmentation, FieldSegmentationConfig::fields());
  return f;
}

void ColorEstimatorConfig::validate() const {
  fields().validate(*this);
  model.validate();
  switching.validate();
  if (withheld_class < -1 || withheld_class > 5)
    throw std::invalid_argument("withheld_class = " + std::to_string(withheld_class) +
                                " (allowed: -1..5)");
}

ColorEstimator::ColorEstimator(const world::FieldMap& map, const world::PinholeCamera& camera,
                               const std::vector<LightingPrior>& priors, const ColorEstimatorConfig& config)
    : config_(config), renderer_(map, camera), filter_(priors, config.model, config.switching), lut_(config.lut_rebuild_sigma) {
  config_.validate();
  lut_.update(filter_.active().classifier());
}

void ColorEstimator::reset() {
  filter_.reset();
  last_t_s_.reset();
  lut_.invalidate();
  lut_.update(filter_.active().classifier());
}

ColorEstimator::Result ColorEstimator::process(double t_s, const cv::Mat& yuv, const Eigen::Isometry3d& map_to_optical) {
  const world::PinholeCamera& cam = renderer_.camera();
  if (yuv.type() != CV_8UC3 || yuv.cols != cam.width_px || yuv.rows != cam.height_px)
    throw std::invalid_argument("ColorEstimator::process: expected a " + std::to_string(cam.width_px) + "x" +
                                std::to_string(cam.height_px) + " YUV image, got " + std::to_string(yuv.cols) + "x" +
                                std::to_string(yuv.rows));
  Result r;
  if (last_t_s_ && t_s < *last_t_s_) {
    reset();
    r.time_reset = true;
  }
  const double dt = last_t_s_ ? t_s - *last_t_s_ : 0.0;
  last_t_s_ = t_s;

  r.expected_labels.create(cam.height_px, cam.width_px, CV_8UC1);
  renderer_.renderImage(map_to_optical, r.expected_labels.ptr<std::uint8_t>(0));
  cv::Mat stats_labels = r.expected_labels;
  if (config_.edge_margin_px > 0) {
    // Keep only pixels whose neighbourhood has one label: erode each label's region by comparing the
    // min and max label over the window.
    const int k = 2 * config_.edge_margin_px + 1;
    const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, {k, k});
    cv::Mat lo, hi;
    cv::erode(r.expected_labels, lo, kernel);
    cv::dilate(r.expected_labels, hi, kernel);
    stats_labels = r.expected_labels.clone();
    stats_labels.setTo(255, lo != hi);
  }
  r.observation = computeColorObservation(yuv, stats_labels, config_.model);
  if (config_.withheld_class >= 0) {
    const int k = config_.model.colorIndex(static_cast<std::uint8_t>(config_.withheld_class));
    if (k >= 0) r.observation.counts[k] = 0;
  }
  filter_.predict(dt);
  r.log_likelihood = filter_.update(r.observation);
  r.active_mode = filter_.activeMode();
  lut_.update(filter_.active().classifier());
  lut_.lut().classifyYuv(yuv, &r.classified);
  return r;
}

void ColorEstimator::classify(const cv::Mat& image, cv::Mat* labels) {
  lut_.update(filter_.active().classifier());
  if (image.type() == CV_8UC2) {
    lut_.lut().classifyUyvy(image, labels);
  } else {
    lut_.lut().classifyYuv(image, labels);
  }
}

}  // namespace adaptive_perception::color
