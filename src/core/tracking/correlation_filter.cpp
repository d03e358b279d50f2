#include "adaptive_perception/tracking/correlation_filter.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace adaptive_perception::tracking {

void CorrelationFilterConfig::validate() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (window_cells < 8 || window_cells > 128)
    fail("window_cells = " + std::to_string(window_cells) + " (allowed: 8..128)");
  if (cell_px < 2 || cell_px > 16)
    fail("cell_px = " + std::to_string(cell_px) + " (allowed: 2..16)");
  if (!(padding >= 1.5 && padding <= 5.0))
    fail("padding = " + std::to_string(padding) + " (allowed: 1.5..5)");
  if (!(min_window_px >= 0.0 && std::isfinite(min_window_px)))
    fail("min_window_px = " + std::to_string(min_window_px) + " (allowed: >= 0)");
  if (!(max_padding >= padding && max_padding <= 10.0))
    fail("max_padding = " + std::to_string(max_padding) + " (allowed: padding..10)");
  if (orientations < 2 || orientations > 18)
    fail("orientations = " + std::to_string(orientations) + " (allowed: 2..18)");
  if (!(label_sigma > 0.0 && label_sigma < 1.0))
    fail("label_sigma = " + std::to_string(label_sigma) + " (allowed: 0 < x < 1)");
  if (!(lambda > 0.0 && std::isfinite(lambda)))
    fail("lambda = " + std::to_string(lambda) + " (allowed: > 0)");
  if (!(learning_rate >= 0.0 && learning_rate <= 1.0))
    fail("learning_rate = " + std::to_string(learning_rate) + " (allowed: 0..1)");
}

std::vector<cv::Mat> gradientCellFeatures(const cv::Mat& window, int cell_px, int orientations) {
  CV_Assert(window.type() == CV_32F && cell_px > 0 && orientations > 0);
  const int rows = window.rows / cell_px, cols = window.cols / cell_px;
  std::vector<cv::Mat> out(orientations + 1);
  for (cv::Mat& m : out) m = cv::Mat::zeros(rows, cols, CV_32F);
  if (rows == 0 || cols == 0) return out;
  cv::Mat gx, gy, mag, angle;
  cv::Sobel(window, gx, CV_32F, 1, 0, 1, 0.5, 0, cv::BORDER_REPLICATE);  // central differences
  cv::Sobel(window, gy, CV_32F, 0, 1, 1, 0.5, 0, cv::BORDER_REPLICATE);
  cv::cartToPolar(gx, gy, mag, angle);  // angle in radians, 0..2 pi
  const float bins_per_rad = static_cast<float>(orientations / CV_PI);
  for (int y = 0; y < rows * cell_px; ++y) {
    const float* m = mag.ptr<float>(y);
    const float* a = angle.ptr<float>(y);
    const float* g = window.ptr<float>(y);
    const int cy = y / cell_px;
    for (int x = 0; x < cols * cell_px; ++x) {
      const int cx = x / cell_px;
      float theta = a[x];
      if (theta >= CV_PI) theta -= static_cast<float>(CV_PI);  // unsigned orientation
      const float f = theta * bins_per_rad - 0.5f;
      const int lo = static_cast<int>(std::floor(f));
      const float w_hi = f - lo;
      const int b0 = (lo + orientations) % orientations, b1 = (lo + 1) % orientations;
      out[b0].at<float>(cy, cx) += m[x] * (1.0f - w_hi);
      out[b1].at<float>(cy, cx) += m[x] * w_hi;
      out[orientations].at<float>(cy, cx) += g[x];
    }
  }
  // Each cell's orientations over the root mean energy of its 3x3 neighbourhood (HOG's block
  // normalisation, one block per cell), clipped so that one strong edge does not rule the window.
  cv::Mat energy = cv::Mat::zeros(rows, cols, CV_32F);
  for (int k = 0; k < orientations; ++k) energy += out[k].mul(out[k]);
  cv::Mat local;
  cv::blur(energy, local, cv::Size(3, 3), cv::Point(-1, -1), cv::BORDER_REPLICATE);
  const double floor_energy = 0.01 * cv::mean(energy)[0] + 1e-8;  // a flat window stays near 0
  cv::Mat norm;
  cv::sqrt(local + floor_energy, norm);
  for (int k = 0; k < orientations; ++k) {
    cv::divide(out[k], norm, out[k]);
    cv::min(out[k], 0.5, out[k]);
  }
  out[orientations] = out[orientations] / (cell_px * cell_px) - 0.5;
  return out;
}

CorrelationFilter::CorrelationFilter(CorrelationFilterConfig config) : config_(config) {
  config_.validate();
}

cv::Mat resampledWindow(const cv::Mat& grey, const cv::Point2d& centre, const cv::Size2d& window_px,
                        const cv::Size& out_size) {
  const double sx = window_px.width / out_size.width, sy = window_px.height / out_size.height;
  const cv::Rect bounds(0, 0, grey.cols, grey.rows);
  // The source region the window reads, with a margin for the interpolation and the blur.
  const double margin = 2.0 + 2.0 * std::max(sx, sy);
  cv::Rect need(static_cast<int>(std::floor(centre.x - window_px.width / 2 - margin)),
                static_cast<int>(std::floor(centre.y - window_px.height / 2 - margin)),
                static_cast<int>(std::ceil(window_px.width + 2 * margin)),
                static_cast<int>(std::ceil(window_px.height + 2 * margin)));
  cv::Rect inside = need & bounds;
  cv::Mat source;
  cv::Point origin = need.tl();
  if (inside.empty()) {  // the window lies wholly outside: the nearest border pixel everywhere
    const int x = std::clamp(static_cast<int>(centre.x), 0, grey.cols - 1);
    const int y = std::clamp(static_cast<int>(centre.y), 0, grey.rows - 1);
    return cv::Mat(out_size, CV_32F, cv::Scalar(grey.at<std::uint8_t>(y, x) / 255.0));
  }
  cv::copyMakeBorder(grey(inside), source, inside.y - need.y, need.br().y - inside.br().y,
                     inside.x - need.x, need.br().x - inside.br().x, cv::BORDER_REPLICATE);
  const double shrink = std::max(sx, sy);
  if (shrink > 1.05) {  // continuous in the scale: no step in the features between scales
    const double sigma = 0.5 * std::sqrt(shrink * shrink - 1.0);
    cv::GaussianBlur(source, source, cv::Size(), sigma, sigma, cv::BORDER_REPLICATE);
  }
  // dst (u, v) reads source at centre + ((u + 0.5) - W / 2) * sx - 0.5 - origin.
  const cv::Matx23d m(sx, 0, centre.x - origin.x - 0.5 + (0.5 - out_size.width / 2.0) * sx,  //
                      0, sy, centre.y - origin.y - 0.5 + (0.5 - out_size.height / 2.0) * sy);
  cv::Mat out8;
  cv::warpAffine(source, out8, cv::Mat(m), out_size, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REPLICATE);
  cv::Mat out;
  out8.convertTo(out, CV_32F, 1.0 / 255.0);
  return out;
}

namespace {

cv::Mat toGrey(const cv::Mat& image) {
  if (image.type() == CV_8UC1) return image;
  if (image.type() == CV_8UC3) {
    cv::Mat g;
    cv::cvtColor(image, g, cv::COLOR_BGR2GRAY);
    return g;
  }
  throw std::invalid_argument("CorrelationFilter: expected a mono8 or bgr8 image");
}

}  // namespace

void CorrelationFilter::init(const cv::Mat& image, const cv::Rect2d& box) {
  if (image.empty()) throw std::invalid_argument("CorrelationFilter::init: empty image");
  if (!(box.width > 0 && box.height > 0))
    throw std::invalid_argument("CorrelationFilter::init: empty box");
  const double aspect = box.width / box.height;
  auto even = [](double v) { return std::clamp(2 * static_cast<int>(std::lround(v / 2)), 8, 512); };
  cols_ = even(config_.window_cells * std::sqrt(aspect));
  rows_ = even(config_.window_cells / std::sqrt(aspect));
  const double padding =
      std::clamp(config_.min_window_px / std::sqrt(box.width * box.height), config_.padding,
                 config_.max_padding);
  window_w0_px_ = box.width * padding;
  window_h0_px_ = box.height * padding;
  cell_scale_px_ = std::sqrt(window_w0_px_ / cols_ * window_h0_px_ / rows_);
  cv::createHanningWindow(hann_, cv::Size(cols_, rows_), CV_32F);
  // The Gaussian label, its peak at cell (0, 0) (zero displacement), wrapped around.
  const double target_cells = std::sqrt(box.width * box.height) / cell_scale_px_;
  const double sigma = config_.label_sigma * target_cells;
  cv::Mat label(rows_, cols_, CV_32F);
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c) {
      const int dr = std::min(r, rows_ - r), dc = std::min(c, cols_ - c);
      label.at<float>(r, c) =
          static_cast<float>(std::exp(-0.5 * (dr * dr + dc * dc) / (sigma * sigma)));
    }
  cv::dft(label, label_spectrum_, cv::DFT_COMPLEX_OUTPUT);
  a_.clear();
  const cv::Mat grey = toGrey(image);
  train(spectra(grey, {box.x + box.width / 2, box.y + box.height / 2}, 1.0), 1.0);
}

std::vector<cv::Mat> CorrelationFilter::spectra(const cv::Mat& image, const cv::Point2d& centre,
                                                double scale) const {
  const cv::Mat grey = toGrey(image);
  const cv::Mat window =
      resampledWindow(grey, centre, {window_w0_px_ * scale, window_h0_px_ * scale},
                      {cols_ * config_.cell_px, rows_ * config_.cell_px});
  std::vector<cv::Mat> features =
      gradientCellFeatures(window, config_.cell_px, config_.orientations);
  std::vector<cv::Mat> out(features.size());
  for (std::size_t c = 0; c < features.size(); ++c)
    cv::dft(features[c].mul(hann_), out[c], cv::DFT_COMPLEX_OUTPUT);
  return out;
}

void CorrelationFilter::train(const std::vector<cv::Mat>& x, double rate) {
  cv::Mat b = cv::Mat::zeros(rows_, cols_, CV_32F);
  std::vector<cv::Mat> a(x.size());
  for (std::size_t c = 0; c < x.size(); ++c) {
    cv::mulSpectrums(label_spectrum_, x[c], a[c], 0, /*conjB=*/true);
    cv::Mat power;
    cv::mulSpectrums(x[c], x[c], power, 0, /*conjB=*/true);  // |X_c|^2, imaginary part 0
    cv::Mat parts[2];
    cv::split(power, parts);
    b += parts[0];
  }
  if (a_.empty() || rate >= 1.0) {
    a_ = a;
    b_ = b;
    return;
  }
  const double keep = 1.0 - rate;
  for (std::size_t c = 0; c < a.size(); ++c) cv::addWeighted(a_[c], keep, a[c], rate, 0.0, a_[c]);
  cv::addWeighted(b_, keep, b, rate, 0.0, b_);
}

cv::Mat CorrelationFilter::response(const cv::Mat& image, const cv::Point2d& centre,
                                    double scale) const {
  if (!initialized()) throw std::logic_error("CorrelationFilter::response before init");
  const std::vector<cv::Mat> z = spectra(image, centre, scale);
  cv::Mat sum = cv::Mat::zeros(rows_, cols_, CV_32FC2), term;
  for (std::size_t c = 0; c < z.size(); ++c) {
    cv::mulSpectrums(a_[c], z[c], term, 0);
    sum += term;
  }
  cv::Mat denominator = b_ + config_.lambda;
  cv::Mat parts[2];
  cv::split(sum, parts);
  cv::divide(parts[0], denominator, parts[0]);
  cv::divide(parts[1], denominator, parts[1]);
  cv::merge(parts, 2, sum);
  cv::Mat wrapped;
  cv::idft(sum, wrapped, cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
  // Zero displacement from (0, 0) to the map's centre (cols / 2, rows / 2).
  cv::Mat out(rows_, cols_, CV_32F);
  const int hr = rows_ / 2, hc = cols_ / 2;
  for (int r = 0; r < rows_; ++r)
    for (int c = 0; c < cols_; ++c)
      out.at<float>((r + hr) % rows_, (c + hc) % cols_) = wrapped.at<float>(r, c);
  return out;
}

double CorrelationFilter::responseAt(const cv::Mat& map, const cv::Point2d& centre, double scale,
                                     double x, double y) const {
  const cv::Size2d cell = cellPx(scale);
  const double u = map.cols / 2 + (x - centre.x) / cell.width;
  const double v = map.rows / 2 + (y - centre.y) / cell.height;
  if (!(u >= 0.0 && v >= 0.0 && u <= map.cols - 1 && v <= map.rows - 1)) return 0.0;
  const int u0 = std::min(static_cast<int>(u), map.cols - 2);
  const int v0 = std::min(static_cast<int>(v), map.rows - 2);
  const double fu = u - u0, fv = v - v0;
  return (1 - fv) * ((1 - fu) * map.at<float>(v0, u0) + fu * map.at<float>(v0, u0 + 1)) +
         fv * ((1 - fu) * map.at<float>(v0 + 1, u0) + fu * map.at<float>(v0 + 1, u0 + 1));
}

void CorrelationFilter::update(const cv::Mat& image, const cv::Point2d& centre, double scale) {
  if (!initialized()) throw std::logic_error("CorrelationFilter::update before init");
  train(spectra(image, centre, scale), config_.learning_rate);
}

}  // namespace adaptive_perception::tracking
