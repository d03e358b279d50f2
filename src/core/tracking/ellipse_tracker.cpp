#include "adaptive_perception/tracking/ellipse_tracker.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace adaptive_perception::tracking {

std::vector<int> ellipseRowHalfWidths(double ax, double ay) {
  const int ry = static_cast<int>(std::floor(ay));
  std::vector<int> half(2 * ry + 1);
  for (int dy = -ry; dy <= ry; ++dy) {
    const double t = 1.0 - (dy / ay) * (dy / ay);
    half[dy + ry] = static_cast<int>(std::floor(ax * std::sqrt(std::max(0.0, t))));
  }
  return half;
}

EllipseWindow::EllipseWindow(const cv::Mat& bin_image, int bins, double ax, double ay,
                             const Histogram& model)
    : bins_(bin_image), half_(ellipseRowHalfWidths(ax, ay)), model_(model) {
  if (bin_image.type() != CV_32S)
    throw std::invalid_argument("EllipseWindow: bin image not CV_32S");
  if (static_cast<int>(model.size()) != bins)
    throw std::invalid_argument("EllipseWindow: model of " + std::to_string(model.size()) +
                                " bins, quantizer " + std::to_string(bins));
  double area = 0.0;
  for (int h : half_) area += 2 * h + 1;
  normalizeMass(&model_, area);
  hist_.assign(bins, 0.0f);
}

void EllipseWindow::add(int bin, float delta) {
  const float before = std::min(hist_[bin], model_[bin]);
  hist_[bin] += delta;
  inter_ += std::min(hist_[bin], model_[bin]) - before;
  pixels_ += delta;
}

void EllipseWindow::place(int cx, int cy) {
  std::fill(hist_.begin(), hist_.end(), 0.0f);
  inter_ = pixels_ = 0.0;
  cx_ = cx;
  cy_ = cy;
  const int ry = static_cast<int>(half_.size() / 2);
  for (int dy = -ry; dy <= ry; ++dy) {
    const int y = cy + dy;
    if (y < 0 || y >= bins_.rows) continue;
    const int* row = bins_.ptr<int>(y);
    const int x0 = std::max(0, cx - half_[dy + ry]);
    const int x1 = std::min(bins_.cols - 1, cx + half_[dy + ry]);
    for (int x = x0; x <= x1; ++x) add(row[x], 1.0f);
  }
}

void EllipseWindow::shiftRight() {
  const int ry = static_cast<int>(half_.size() / 2);
  for (int dy = -ry; dy <= ry; ++dy) {
    const int y = cy_ + dy;
    if (y < 0 || y >= bins_.rows) continue;
    const int* row = bins_.ptr<int>(y);
    const int leave = cx_ - half_[dy + ry];
    const int enter = cx_ + half_[dy + ry] + 1;
    if (leave >= 0 && leave < bins_.cols) add(row[leave], -1.0f);
    if (enter >= 0 && enter < bins_.cols) add(row[enter], 1.0f);
  }
  ++cx_;
}

void EllipseTrackerConfig::validate() const {
  fields().validate(*this);
  quantizer.validate();
  if (!(scale_step >= 0.0 && scale_step < 0.5))
    throw std::invalid_argument("scale_step must be in [0, 0.5)");
  if (!(lost_search_gain >= 1.0)) throw std::invalid_argument("lost_search_gain must be >= 1");
  if (!(min_axis_px > 0.0)) throw std::invalid_argument("min_axis_px must be > 0");
}

EllipseTracker::EllipseTracker(EllipseTrackerConfig config) : config_(config) {
  config_.validate();
}

void EllipseTracker::init(const cv::Mat& bgr8, const Ellipse& e) {
  const cv::Mat bins = config_.quantizer.binImage(bgr8);
  EllipseWindow w(bins, config_.quantizer.size(), e.ax, e.ay,
                  Histogram(config_.quantizer.size(), 1.0f));
  w.place(static_cast<int>(std::lround(e.cx)), static_cast<int>(std::lround(e.cy)));
  if (w.pixels() <= 0)
    throw std::invalid_argument("EllipseTracker::init: the ellipse holds no pixel of the image");
  model_ = w.histogram();
  normalizeMass(&model_, 1.0);
  ellipse_ = e;
  initialized_ = true;
  lost_ = false;
}

void EllipseTracker::setModel(const Histogram& model) {
  if (static_cast<int>(model.size()) != config_.quantizer.size())
    throw std::invalid_argument("setModel: histogram of " + std::to_string(model.size()) +
                                " bins, quantizer " + std::to_string(config_.quantizer.size()));
  model_ = model;
  normalizeMass(&model_, 1.0);
}

EllipseResult EllipseTracker::track(const cv::Mat& bgr8) {
  return trackBins(config_.quantizer.binImage(bgr8));
}

EllipseResult EllipseTracker::trackBins(const cv::Mat& bin_image) {
  if (!initialized_) throw std::logic_error("EllipseTracker::track before init");
  const int radius = static_cast<int>(
      std::lround(config_.search_radius_px * (lost_ ? config_.lost_search_gain : 1.0)));
  std::vector<double> scales = {1.0};
  if (config_.scale_step > 0.0) scales = {1.0, 1.0 - config_.scale_step, 1.0 + config_.scale_step};
  EllipseResult best;
  best.intersection = -1.0;
  const int cx0 = static_cast<int>(std::lround(ellipse_.cx));
  const int cy0 = static_cast<int>(std::lround(ellipse_.cy));
  for (double s : scales) {
    const double ax = std::max(config_.min_axis_px, ellipse_.ax * s);
    const double ay = std::max(config_.min_axis_px, ellipse_.ay * s);
    EllipseWindow w(bin_image, config_.quantizer.size(), ax, ay, model_);
    for (int dy = -radius; dy <= radius; ++dy) {
      w.place(cx0 - radius, cy0 + dy);
      for (int dx = -radius; dx <= radius; ++dx) {
        if (dx > -radius) w.shiftRight();
        // Ties keep the earlier (unscaled, nearer the top-left) candidate: deterministic.
        if (w.pixels() > 0 && w.intersection() > best.intersection + 1e-12) {
          best.intersection = w.intersection();
          best.ellipse = {static_cast<double>(w.cx()), static_cast<double>(w.cy()), ax, ay};
        }
      }
    }
  }
  if (best.intersection < 0.0) {  // the whole window left the image
    best.ellipse = ellipse_;
    best.intersection = 0.0;
  }
  best.lost = best.intersection < config_.lost_threshold;
  lost_ = best.lost;
  if (!best.lost) ellipse_ = best.ellipse;
  if (best.intersection > config_.update_threshold && config_.update_rate > 0.0) {
    EllipseWindow w(bin_image, config_.quantizer.size(), best.ellipse.ax, best.ellipse.ay, model_);
    w.place(static_cast<int>(best.ellipse.cx), static_cast<int>(best.ellipse.cy));
    updateModel(&model_, w.histogram(), config_.update_rate);
    best.model_updated = true;
  }
  return best;
}

}  // namespace adaptive_perception::tracking
