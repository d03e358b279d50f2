#include "adaptive_perception/tracking/scale_filter.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "adaptive_perception/tracking/correlation_filter.h"

namespace adaptive_perception::tracking {

void ScaleFilterConfig::validate() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (scales < 3 || scales > 129 || scales % 2 == 0)
    fail("scales = " + std::to_string(scales) + " (allowed: odd, 3..129)");
  if (!(scale_step > 0.0 && scale_step < 0.5))
    fail("scale_step = " + std::to_string(scale_step) + " (allowed: 0 < x < 0.5)");
  if (!(model_area_px >= 64.0 && model_area_px <= 65536.0))
    fail("model_area_px = " + std::to_string(model_area_px) + " (allowed: 64..65536)");
  if (!(padding >= 1.0 && padding <= 5.0))
    fail("padding = " + std::to_string(padding) + " (allowed: 1..5)");
  if (cell_px < 2 || cell_px > 16)
    fail("cell_px = " + std::to_string(cell_px) + " (allowed: 2..16)");
  if (orientations < 2 || orientations > 18)
    fail("orientations = " + std::to_string(orientations) + " (allowed: 2..18)");
  if (!(label_sigma_factor > 0.0 && label_sigma_factor <= 10.0))
    fail("label_sigma_factor = " + std::to_string(label_sigma_factor) + " (allowed: 0 < x <= 10)");
  if (!(lambda > 0.0 && std::isfinite(lambda)))
    fail("lambda = " + std::to_string(lambda) + " (allowed: > 0)");
  if (!(learning_rate >= 0.0 && learning_rate <= 1.0))
    fail("learning_rate = " + std::to_string(learning_rate) + " (allowed: 0..1)");
}

namespace {

void checkTarget(const char* what, const cv::Mat& grey, const cv::Point2d& centre,
                 const cv::Size2d& target_px) {
  if (grey.empty() || grey.type() != CV_8UC1)
    throw std::invalid_argument(std::string(what) + ": expected a non-empty mono8 image");
  // (A million pixels a side is beyond any camera; the window's pixel arithmetic is int.)
  if (!(target_px.width >= 1.0 && target_px.height >= 1.0 && target_px.width <= 1e6 &&
        target_px.height <= 1e6))
    throw std::invalid_argument(std::string(what) +
                                ": target not 1 to 1e6 pixels a side (or not finite)");
  if (!(std::abs(centre.x) <= 1e6 && std::abs(centre.y) <= 1e6))
    throw std::invalid_argument(std::string(what) + ": centre not finite or beyond 1e6 pixels");
}

}  // namespace

ScaleFilter::ScaleFilter(ScaleFilterConfig config) : config_(config) { config_.validate(); }

void ScaleFilter::init(const cv::Mat& grey, const cv::Point2d& centre,
                       const cv::Size2d& target_px) {
  checkTarget("ScaleFilter::init", grey, centre, target_px);
  // The model: the target's aspect at model_area_px, at least two cells a side (a small target is
  // enlarged: at its own size a 10 x 9 px target would have 2 x 2 cells).
  const double shrink =
      std::sqrt(config_.model_area_px / target_px.area()) / config_.padding;
  const int c = config_.cell_px;
  auto cells = [&](double px) { return std::max(2, static_cast<int>(std::lround(px / c))); };
  model_px_ = {cells(target_px.width * config_.padding * shrink) * c,
               cells(target_px.height * config_.padding * shrink) * c};
  const int n = config_.scales;
  hann_.create(1, n, CV_32F);
  cv::Mat label(1, n, CV_32F);
  const double sigma = config_.label_sigma_factor * std::sqrt(static_cast<double>(n));
  for (int i = 0; i < n; ++i) {
    hann_.at<float>(0, i) =
        static_cast<float>(0.5 - 0.5 * std::cos(2.0 * CV_PI * (i + 1) / (n + 1)));
    const double d = i - (n - 1) / 2;
    label.at<float>(0, i) = static_cast<float>(std::exp(-0.5 * d * d / (sigma * sigma)));
  }
  cv::dft(label, label_, cv::DFT_COMPLEX_OUTPUT | cv::DFT_ROWS);
  b_.release();
  train(spectra(grey, centre, target_px), 1.0);
}

cv::Mat ScaleFilter::spectra(const cv::Mat& grey, const cv::Point2d& centre,
                             const cv::Size2d& target) const {
  const cv::Size2d target_px(target.width * config_.padding, target.height * config_.padding);
  const int n = config_.scales, half = (n - 1) / 2;
  // The largest sample's window, read once at the model's resolution (smoothed as it shrinks):
  // each scale is then resampled from it, at most (1 + step)^half (1.37 by default) further.
  const double largest = std::pow(1.0 + config_.scale_step, half);
  // Source pixels an image pixel (the model's resolution; x and y differ by the cells' rounding).
  const double rx = model_px_.width / target_px.width, ry = model_px_.height / target_px.height;
  const int margin = 2;
  const cv::Size source_size(static_cast<int>(std::ceil(model_px_.width * largest)) + 2 * margin,
                             static_cast<int>(std::ceil(model_px_.height * largest)) + 2 * margin);
  const cv::Mat source = resampledWindow(
      grey, centre,
      {source_size.width / rx, source_size.height / ry}, source_size);
  cv::Mat f;
  cv::Mat window;
  for (int i = 0; i < n; ++i) {
    const double factor = std::pow(1.0 + config_.scale_step, i - half);
    // dst (u, v) reads source at its centre + ((u + 0.5) - W / 2) * factor - 0.5: a model pixel
    // spans `factor` source pixels.
    const double k = factor;
    const cv::Matx23d m(k, 0, source.cols / 2.0 - 0.5 + (0.5 - model_px_.width / 2.0) * k,  //
                        0, k, source.rows / 2.0 - 0.5 + (0.5 - model_px_.height / 2.0) * k);
    cv::warpAffine(source, window, cv::Mat(m), model_px_, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                   cv::BORDER_REPLICATE);
    const std::vector<cv::Mat> cells =
        gradientCellFeatures(window, config_.cell_px, config_.orientations);
    if (f.empty()) f.create(static_cast<int>(cells.size() * cells[0].total()), n, CV_32F);
    int row = 0;
    const float w = hann_.at<float>(0, i);
    for (const cv::Mat& channel : cells)
      for (auto it = channel.begin<float>(); it != channel.end<float>(); ++it)
        f.at<float>(row++, i) = *it * w;
  }
  cv::Mat spectrum;
  cv::dft(f, spectrum, cv::DFT_COMPLEX_OUTPUT | cv::DFT_ROWS);
  return spectrum;
}

void ScaleFilter::train(const cv::Mat& f, double rate) {
  cv::Mat a;
  cv::mulSpectrums(cv::repeat(label_, f.rows, 1), f, a, cv::DFT_ROWS, /*conjB=*/true);
  cv::Mat power;
  cv::mulSpectrums(f, f, power, cv::DFT_ROWS, /*conjB=*/true);  // |F_l|^2, imaginary part 0
  cv::Mat parts[2];
  cv::split(power, parts);
  cv::Mat b;
  cv::reduce(parts[0], b, 0, cv::REDUCE_SUM, CV_32F);
  if (b_.empty() || rate >= 1.0) {
    a_ = a;
    b_ = b;
    return;
  }
  cv::addWeighted(a_, 1.0 - rate, a, rate, 0.0, a_);
  cv::addWeighted(b_, 1.0 - rate, b, rate, 0.0, b_);
}

double ScaleFilter::estimate(const cv::Mat& grey, const cv::Point2d& centre,
                             const cv::Size2d& target_px) const {
  if (!initialized()) throw std::logic_error("ScaleFilter::estimate before init");
  checkTarget("ScaleFilter::estimate", grey, centre, target_px);
  const cv::Mat z = spectra(grey, centre, target_px);
  cv::Mat terms;
  cv::mulSpectrums(a_, z, terms, cv::DFT_ROWS);
  cv::Mat sum;
  cv::reduce(terms, sum, 0, cv::REDUCE_SUM, CV_32F);
  cv::Mat parts[2];
  cv::split(sum, parts);
  const cv::Mat denominator = b_ + config_.lambda;
  cv::divide(parts[0], denominator, parts[0]);
  cv::divide(parts[1], denominator, parts[1]);
  cv::merge(parts, 2, sum);
  cv::Mat y;
  cv::idft(sum, y, cv::DFT_REAL_OUTPUT | cv::DFT_SCALE | cv::DFT_ROWS);
  cv::Point peak;
  cv::minMaxLoc(y, nullptr, nullptr, nullptr, &peak);
  const int n = config_.scales, i = peak.x;
  double offset = 0.0;  // the vertex of the parabola through the peak and its neighbours
  if (i > 0 && i < n - 1) {
    const double l = y.at<float>(0, i - 1), m = y.at<float>(0, i), r = y.at<float>(0, i + 1);
    const double curvature = l - 2.0 * m + r;
    if (curvature < 0.0) offset = std::clamp(0.5 * (l - r) / curvature, -0.5, 0.5);
  }
  return std::pow(1.0 + config_.scale_step, i - (n - 1) / 2 + offset);
}

void ScaleFilter::update(const cv::Mat& grey, const cv::Point2d& centre,
                         const cv::Size2d& target_px) {
  if (!initialized()) throw std::logic_error("ScaleFilter::update before init");
  checkTarget("ScaleFilter::update", grey, centre, target_px);
  train(spectra(grey, centre, target_px), config_.learning_rate);
}

}  // namespace adaptive_perception::tracking
