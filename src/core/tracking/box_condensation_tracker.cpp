#include "adaptive_perception/tracking/box_condensation_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "adaptive_perception/math/particle_set.h"
#include "box_regions.h"

namespace adaptive_perception::tracking {

void BoxTrackerConfig::validate() const {
  fields().validate(*this);
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (bins_per_channel < 2 || bins_per_channel > 64 ||
      (bins_per_channel & (bins_per_channel - 1)) != 0)
    fail("bins_per_channel = " + std::to_string(bins_per_channel) +
         " (allowed: a power of two, 2..64)");
  if (!(position_noise > 0.0 && std::isfinite(position_noise)))
    fail("position_noise = " + std::to_string(position_noise) + " (allowed: > 0)");
  if (!(scale_noise >= 0.0 && scale_noise < 1.0))
    fail("scale_noise = " + std::to_string(scale_noise) + " (allowed: 0..1)");
  if (!(wide_fraction >= 0.0 && wide_fraction < 1.0))
    fail("wide_fraction = " + std::to_string(wide_fraction) + " (allowed: 0 <= x < 1)");
  if (!(wide_noise > 0.0 && std::isfinite(wide_noise)))
    fail("wide_noise = " + std::to_string(wide_noise) + " (allowed: > 0)");
  if (!(aspect_noise >= 0.0 && aspect_noise < 1.0))
    fail("aspect_noise = " + std::to_string(aspect_noise) + " (allowed: 0..1)");
  if (!(velocity_gain >= 0.0 && velocity_gain <= 1.0))
    fail("velocity_gain = " + std::to_string(velocity_gain) + " (allowed: 0..1)");
  if (!(ring_scale > 1.0 && ring_scale < 10.0))
    fail("ring_scale = " + std::to_string(ring_scale) + " (allowed: 1 < x < 10)");
  if (!(surround_scale > 1.0 && surround_scale < 10.0))
    fail("surround_scale = " + std::to_string(surround_scale) + " (allowed: 1 < x < 10)");
  if (!(score_gain > 0.0 && std::isfinite(score_gain)))
    fail("score_gain = " + std::to_string(score_gain) + " (allowed: > 0)");
  if (!(learning_rate >= 0.0 && learning_rate <= 1.0))
    fail("learning_rate = " + std::to_string(learning_rate) + " (allowed: 0..1)");
  if (!(update_min_score >= -1.0 && update_min_score <= 1.0))
    fail("update_min_score = " + std::to_string(update_min_score) + " (allowed: -1..1)");
  if (!(lost_growth >= 1.0 && lost_growth < 10.0))
    fail("lost_growth = " + std::to_string(lost_growth) + " (allowed: 1..10)");
  if (!(min_side_px > 0.0 && std::isfinite(min_side_px)))
    fail("min_side_px = " + std::to_string(min_side_px) + " (allowed: > 0)");
  if (template_cells != 0 && (template_cells < 4 || template_cells > 64))
    fail("template_cells = " + std::to_string(template_cells) + " (allowed: 0 or 4..64)");
  if (!(template_gain >= 0.0 && std::isfinite(template_gain)))
    fail("template_gain = " + std::to_string(template_gain) + " (allowed: >= 0)");
  if (scale_search_steps < 0 || scale_search_steps > 20)
    fail("scale_search_steps = " + std::to_string(scale_search_steps) + " (allowed: 0..20)");
  if (!(scale_step > 0.0 && scale_step < 1.0))
    fail("scale_step = " + std::to_string(scale_step) + " (allowed: 0 < x < 1)");
  if (!(template_rate >= 0.0 && template_rate <= 1.0))
    fail("template_rate = " + std::to_string(template_rate) + " (allowed: 0..1)");
  if (filter_scales < 0 || filter_scales > 5)
    fail("filter_scales = " + std::to_string(filter_scales) + " (allowed: 0..5)");
  if (!(filter_scale_step > 0.0 && filter_scale_step < 0.5))
    fail("filter_scale_step = " + std::to_string(filter_scale_step) + " (allowed: 0 < x < 0.5)");
  if (!(redetect_after_frames >= 0 && redetect_after_frames <= 1000))
    fail("redetect_after_frames = " + std::to_string(redetect_after_frames) +
         " (allowed: 0..1000)");
  if (!(redetect_places >= 1 && redetect_places <= 100))
    fail("redetect_places = " + std::to_string(redetect_places) + " (allowed: 1..100)");
  if (!(scale_filter_share >= 0.0 && scale_filter_share <= 1.0))
    fail("scale_filter_share = " + std::to_string(scale_filter_share) + " (allowed: 0..1)");
  if (scale_filter_share > 0.0 && min_side_px < 1.0)
    fail("min_side_px = " + std::to_string(min_side_px) +
         " (allowed with scale_filter_share > 0: >= 1, the scale filter's smallest target)");
  if (!(filter_scale_share >= 0.0 && filter_scale_share <= 1.0))
    fail("filter_scale_share = " + std::to_string(filter_scale_share) + " (allowed: 0..1)");
  try {
    filter.validate();
  } catch (const std::invalid_argument& e) {
    fail(std::string("filter.") + e.what());
  }
  try {
    scale.validate();
  } catch (const std::invalid_argument& e) {
    fail(std::string("scale.") + e.what());
  }
}

using namespace box_regions;

BoxCondensationTracker::BoxCondensationTracker(BoxTrackerConfig config, std::uint64_t seed)
    : config_(config),
      rng_(seed),
      filter_((config.validate(), config.filter)),
      scale_filter_(config.scale) {}

double BoxCondensationTracker::FilterMaps::at(const CorrelationFilter& f, double step, double x,
                                              double y, double sample_log_scale) const {
  if (maps.empty()) return 0.0;
  const int k_max = static_cast<int>(maps.size() / 2);
  const int k = std::clamp(static_cast<int>(std::lround((sample_log_scale - log_scale) / step)),
                           -k_max, k_max);
  return f.responseAt(maps[k + k_max], centre, std::exp(log_scale + k * step), x, y);
}

cv::Rect2d BoxCondensationTracker::boxOf(const Sample& s) const {
  const double w = w0_ * std::exp(s.log_scale + 0.5 * s.log_aspect);
  const double h = h0_ * std::exp(s.log_scale - 0.5 * s.log_aspect);
  return {s.x - w / 2, s.y - h / 2, w, h};
}

void BoxCondensationTracker::smoothedGrey(const cv::Mat& image, const cv::Rect& region,
                                          double box_side, cv::Mat* grey) const {
  cv::Mat g;
  if (image.channels() == 1)
    image(region).convertTo(g, CV_32F);
  else {
    cv::Mat g8;
    cv::cvtColor(image(region), g8, cv::COLOR_BGR2GRAY);
    g8.convertTo(g, CV_32F);
  }
  // Anti-aliasing for a grid of template_cells a side: sigma of half a cell.
  const double sigma = 0.5 * box_side / std::max(1, config_.template_cells);
  if (sigma > 0.7)
    cv::GaussianBlur(g, *grey, cv::Size(), sigma, sigma, cv::BORDER_REPLICATE);
  else
    *grey = g;
}

std::vector<float> BoxCondensationTracker::patch(const cv::Mat& grey, const cv::Point& origin,
                                                 const cv::Rect2d& box) const {
  const int c = config_.template_cells;
  std::vector<float> p(static_cast<std::size_t>(c) * c);
  double mean = 0.0;
  for (int j = 0; j < c; ++j) {
    const int y = std::clamp(static_cast<int>(box.y + (j + 0.5) * box.height / c) - origin.y, 0,
                             grey.rows - 1);
    const float* row = grey.ptr<float>(y);
    for (int i = 0; i < c; ++i) {
      const int x = std::clamp(static_cast<int>(box.x + (i + 0.5) * box.width / c) - origin.x, 0,
                               grey.cols - 1);
      p[j * c + i] = row[x];
      mean += row[x];
    }
  }
  mean /= p.size();
  double norm = 0.0;
  for (float& v : p) {
    v = static_cast<float>(v - mean);
    norm += static_cast<double>(v) * v;
  }
  if (norm < 1e-6) return {};
  const float k = static_cast<float>(1.0 / std::sqrt(norm));
  for (float& v : p) v *= k;
  return p;
}

void BoxCondensationTracker::init(const cv::Mat& image, const cv::Rect2d& box) {
  if (image.empty() || (image.type() != CV_8UC3 && image.type() != CV_8UC1))
    throw std::invalid_argument("BoxCondensationTracker::init: expected a bgr8 or mono8 image");
  if (!(box.width >= config_.min_side_px && box.height >= config_.min_side_px))
    throw std::invalid_argument("BoxCondensationTracker::init: the box must be at least " +
                                std::to_string(config_.min_side_px) + " px a side");
  if ((box & cv::Rect2d(0, 0, image.cols, image.rows)).area() <= 0)
    throw std::invalid_argument("BoxCondensationTracker::init: the box lies outside the image");
  w0_ = box.width;
  h0_ = box.height;
  estimate_ = {box.x + box.width / 2, box.y + box.height / 2, 0.0, 0.0};
  vx_ = vy_ = 0.0;
  histograms(image, box, &h_object_, &h_surround_);
  h_distractor_.clear();
  out_distractors_.clear();
  template_.clear();
  if (config_.template_cells > 0) {
    const cv::Rect region = covering(grown(box, 1.2), cv::Rect(0, 0, image.cols, image.rows));
    cv::Mat grey;
    smoothedGrey(image, region, std::sqrt(box.area()), &grey);
    template_ = patch(grey, region.tl(), box);
  }
  if (config_.filter_gain > 0.0) filter_.init(image, box);
  if (config_.scale_filter_share > 0.0) {
    cv::Mat grey = image;
    if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
    scale_filter_.init(grey, {box.x + box.width / 2, box.y + box.height / 2}, box.size());
  }
  samples_.assign(config_.samples, estimate_);
  weights_.assign(config_.samples, 1.0 / config_.samples);
  lost_frames_ = lost_run_ = 0;
  searching_ = false;
  mean_peak_ = mean_apce_ = mean_colour_ = 0.0;
  response_frames_ = 0;
  initialized_ = true;
}

BoxTrackResult BoxCondensationTracker::track(const cv::Mat& image) {
  if (!initialized_) throw std::logic_error("BoxCondensationTracker::track before init");
  if (image.empty() || (image.type() != CV_8UC3 && image.type() != CV_8UC1))
    throw std::invalid_argument("BoxCondensationTracker::track: expected a bgr8 or mono8 image");
  const cv::Rect bounds(0, 0, image.cols, image.rows);
  const int n = config_.samples;
  out_distractors_.clear();

  // 1. Resample, then move and spread (wider while lost: re-detection).
  const std::vector<std::size_t> parents =
      math::resampleIndices(weights_, n, math::ResamplingScheme::kSystematic, rng_);
  const double growth = std::pow(config_.lost_growth, std::min(lost_frames_, 12));
  const cv::Rect2d last = boxOf(estimate_);
  const double side = std::sqrt(last.width * last.height);
  const double sd_pos = config_.position_noise * side * growth;
  const double sd_scale = config_.scale_noise * std::sqrt(growth);
  const double sd_aspect = config_.aspect_noise * std::sqrt(growth);
  const double min_log = std::log(config_.min_side_px / std::min(w0_, h0_));
  const double max_log = std::log(std::max(image.cols, image.rows) / std::max(w0_, h0_));
  std::vector<Sample> next(n);
  for (int i = 0; i < n; ++i) {
    const Sample& p = samples_[parents[i]];
    Sample s;
    const double sd = i < config_.wide_fraction * n
                          ? std::max(sd_pos, config_.wide_noise * side * growth)
                          : sd_pos;
    s.x = std::clamp(p.x + config_.velocity_gain * vx_ + rng_.gaussian(0.0, sd), 0.0,
                     static_cast<double>(image.cols));
    s.y = std::clamp(p.y + config_.velocity_gain * vy_ + rng_.gaussian(0.0, sd), 0.0,
                     static_cast<double>(image.rows));
    s.log_scale =
        std::clamp(p.log_scale + rng_.gaussian(0.0, sd_scale), min_log, std::max(min_log, max_log));
    s.log_aspect = std::clamp(p.log_aspect + rng_.gaussian(0.0, sd_aspect), -1.5, 1.5);
    next[i] = s;
  }
  samples_.swap(next);

  // The correlation filter's maps about the predicted centre, and the samples drawn about the
  // best peak.
  cv::Mat grey_image;
  FilterMaps filter_maps;
  double peak_now = 0.0, apce_now = 0.0;
  const bool use_filter = config_.filter_gain > 0.0 && filter_.initialized();
  const bool use_scale_filter = config_.scale_filter_share > 0.0 && scale_filter_.initialized();
  if (use_filter || use_scale_filter) {
    if (image.channels() == 1)
      grey_image = image;
    else
      cv::cvtColor(image, grey_image, cv::COLOR_BGR2GRAY);
  }
  if (use_filter) {
    filter_maps.centre = {estimate_.x + config_.velocity_gain * vx_,
                          estimate_.y + config_.velocity_gain * vy_};
    filter_maps.log_scale = estimate_.log_scale;
    double best_value = -1e300;
    int best_map = 0;
    cv::Point2d best_at = filter_maps.centre;
    double best_log = estimate_.log_scale;
    for (int k = -config_.filter_scales; k <= config_.filter_scales; ++k) {
      const double log_scale = estimate_.log_scale + k * config_.filter_scale_step;
      filter_maps.maps.push_back(
          filter_.response(grey_image, filter_maps.centre, std::exp(log_scale)));
      double value = 0.0;
      cv::Point at;
      cv::minMaxLoc(filter_maps.maps.back(), nullptr, &value, nullptr, &at);
      if (value > best_value) {
        const cv::Size2d cell = filter_.cellPx(std::exp(log_scale));
        best_value = value;
        best_map = static_cast<int>(filter_maps.maps.size()) - 1;
        best_log = log_scale;
        best_at = {filter_maps.centre.x + (at.x - filter_.cols() / 2) * cell.width,
                   filter_maps.centre.y + (at.y - filter_.rows() / 2) * cell.height};
      }
    }
    // The best map's peak and sharpness (APCE).
    {
      const cv::Mat& map = filter_maps.maps[best_map];
      double lo = 0.0, hi = 0.0;
      cv::minMaxLoc(map, &lo, &hi);
      cv::Mat d = map - lo;
      const double energy = cv::mean(d.mul(d))[0];
      peak_now = hi;
      apce_now = energy > 0.0 ? (hi - lo) * (hi - lo) / energy : 0.0;
    }
    const int drawn = static_cast<int>(config_.peak_fraction * n);
    const cv::Size2d cell = filter_.cellPx(std::exp(best_log));
    for (int i = n - drawn; i < n; ++i) {
      Sample& s = samples_[i];
      s.x = std::clamp(best_at.x + rng_.gaussian(0.0, 0.5 * cell.width), 0.0,
                       static_cast<double>(image.cols));
      s.y = std::clamp(best_at.y + rng_.gaussian(0.0, 0.5 * cell.height), 0.0,
                       static_cast<double>(image.rows));
      s.log_scale = std::clamp(best_log + rng_.gaussian(0.0, sd_scale), min_log,
                               std::max(min_log, max_log));
    }
  }
  auto filter_score = [&](const Sample& s) {
    return use_filter ? filter_maps.at(filter_, config_.filter_scale_step, s.x, s.y, s.log_scale)
                      : 0.0;
  };

  // 2. The object likelihood over the region the samples' rings span, and its summed-area table.
  cv::Rect2d span = grown(boxOf(samples_[0]), config_.ring_scale);
  for (const Sample& s : samples_) span |= grown(boxOf(s), config_.ring_scale);
  BoxTrackResult out;
  out.search = covering(span, bounds);
  if (out.search.empty()) out.search = bounds;
  const int nb = static_cast<int>(h_object_.size());
  const std::vector<float> lut = objectLikelihood();
  cv::Mat bins;
  binImage(image, out.search, &bins);
  const cv::Mat likelihood = lookUp(bins, lut);
  cv::Mat sat;
  cv::integral(likelihood, sat, CV_64F);
  out.likelihood = likelihood;
  auto score = [&](const cv::Rect2d& box) {
    return ringScore(sat, out.search.tl(), box, config_.ring_scale);
  };

  // The appearance cue: normalised cross-correlation of the grey template.
  cv::Mat grey;
  const bool use_template = !template_.empty() && config_.template_gain > 0.0;
  if (use_template) smoothedGrey(image, out.search, side, &grey);
  auto ncc = [&](const cv::Rect2d& box) {
    const std::vector<float> p = patch(grey, out.search.tl(), box);
    if (p.empty()) return 0.0;
    double s = 0.0;
    for (std::size_t k = 0; k < p.size(); ++k) s += static_cast<double>(p[k]) * template_[k];
    return s;
  };

  // 3. Weights, and the estimate from the samples near the best one.
  std::vector<double> log_w(n);
  for (int i = 0; i < n; ++i) {
    const cv::Rect2d box = boxOf(samples_[i]);
    log_w[i] = config_.score_gain * score(box) +
               (use_template ? config_.template_gain * ncc(box) : 0.0) +
               config_.filter_gain * filter_score(samples_[i]);
  }
  math::normalizeLogWeights(log_w, &weights_);
  const int best =
      static_cast<int>(std::max_element(weights_.begin(), weights_.end()) - weights_.begin());
  const Sample& b = samples_[best];
  const cv::Rect2d best_box = boxOf(b);
  const double near = 0.5 * std::sqrt(best_box.width * best_box.height);
  double sw = 0.0;
  Sample mean{0, 0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const Sample& s = samples_[i];
    if (std::hypot(s.x - b.x, s.y - b.y) > near) continue;
    sw += weights_[i];
    mean.x += weights_[i] * s.x;
    mean.y += weights_[i] * s.y;
    mean.log_scale += weights_[i] * s.log_scale;
    mean.log_aspect += weights_[i] * s.log_aspect;
  }
  mean = sw > 0 ? Sample{mean.x / sw, mean.y / sw, mean.log_scale / sw, mean.log_aspect / sw} : b;
  if (use_filter && config_.filter_scale_share > 0.0) {
    // The scale whose map answers best at the estimate's centre, blended into the samples'.
    double best_response = -1e300, best_log = mean.log_scale;
    for (int k = -config_.filter_scales; k <= config_.filter_scales; ++k) {
      const double log_scale = filter_maps.log_scale + k * config_.filter_scale_step;
      const double r = filter_maps.at(filter_, config_.filter_scale_step, mean.x, mean.y, log_scale);
      if (r > best_response) {
        best_response = r;
        best_log = log_scale;
      }
    }
    mean.log_scale += config_.filter_scale_share * (best_log - mean.log_scale);
  }
  if (use_scale_filter) {
    // The scale the scale filter finds at the estimate's centre, about the last estimate's, at
    // most two sd of the samples' own scale change a frame (scale_noise) from it: a look-alike
    // pattern at another scale is not a target that grew by a third in a frame.
    const Sample last_size{mean.x, mean.y, estimate_.log_scale, mean.log_aspect};
    const double factor =
        scale_filter_.estimate(grey_image, {mean.x, mean.y}, boxOf(last_size).size());
    const double bound = 2.0 * config_.scale_noise;
    const double found = estimate_.log_scale + std::clamp(std::log(factor), -bound, bound);
    mean.log_scale += config_.scale_filter_share * (found - mean.log_scale);
  }
  if (use_template && config_.scale_search_steps > 0) {
    double best_ncc = -2.0, best_log = mean.log_scale;
    for (int k = -config_.scale_search_steps; k <= config_.scale_search_steps; ++k) {
      const Sample s{mean.x, mean.y, mean.log_scale + k * config_.scale_step, mean.log_aspect};
      const double c = ncc(boxOf(s));
      if (c > best_ncc) {
        best_ncc = c;
        best_log = s.log_scale;
      }
    }
    mean.log_scale = best_log;
  }
  // The estimate's log-weight over score_gain: the colour score plus the template's share, so that
  // a target the template still finds (a grey one, whose colours say little) is not lost.
  const cv::Rect2d mean_box = boxOf(mean);
  const double confidence =
      score(mean_box) +
      (use_template ? config_.template_gain / config_.score_gain * ncc(mean_box) : 0.0) +
      config_.filter_gain / config_.score_gain * filter_score(mean);
  const bool colour_lost = confidence < config_.lost_score;
  // The filter's response and the colour score against their means over the frames so far.
  out.response_peak = peak_now;
  out.response_apce = apce_now;
  const double colour_now = score(mean_box);
  out.unreliable = use_filter && response_frames_ > 0 &&
                   (peak_now < config_.reliable_peak_ratio * mean_peak_ ||
                    apce_now < config_.reliable_apce_ratio * mean_apce_) &&
                   colour_now < config_.reliable_peak_ratio * mean_colour_;
  if (use_filter) {
    ++response_frames_;
    mean_peak_ += (peak_now - mean_peak_) / response_frames_;
    mean_apce_ += (apce_now - mean_apce_) / response_frames_;
    mean_colour_ += (colour_now - mean_colour_) / response_frames_;
  }
  out.lost = colour_lost || out.unreliable;
  // Re-detection: the cues' means as they were when the target was last followed are kept for
  // the search (the means go on averaging the lost frames, and the models learn what stands in
  // the target's place, so the flag alone fades while the target is still away).
  if (out.lost && lost_run_ == 0 && !searching_) {
    reference_peak_ = mean_peak_;
    reference_colour_ = mean_colour_;
    reference_apce_ = mean_apce_;
    reference_log_scale_ = estimate_.log_scale;
    reference_log_aspect_ = estimate_.log_aspect;
  }
  lost_run_ = out.lost ? lost_run_ + 1 : 0;
  if (config_.redetect_after_frames > 0 && lost_run_ >= config_.redetect_after_frames)
    searching_ = true;
  if (searching_ && peak_now >= config_.reliable_peak_ratio * reference_peak_ &&
      colour_now >= config_.reliable_peak_ratio * reference_colour_)
    searching_ = false;  // the estimate answers as the target did: found where it is
  Sample found;
  if (use_filter && searching_ && redetect(image, grey_image, lut, peak_now, colour_now, &found)) {
    // Taken back: the samples start again at the place found; nothing is learnt from this frame.
    out.redetected = true;
    out.lost = out.unreliable = false;
    // The means took in the lost frames: they start again from those of when it was followed.
    mean_peak_ = reference_peak_;
    mean_apce_ = reference_apce_;
    mean_colour_ = reference_colour_;
    lost_run_ = lost_frames_ = 0;
    searching_ = false;
    vx_ = vy_ = 0.0;
    estimate_ = found;
    samples_.assign(n, found);
    weights_.assign(n, 1.0 / n);
    out.box = boxOf(estimate_);
    out.confidence = confidence;
    out.samples.assign(n, out.box);
    out.weights = weights_;
    return out;
  }
  if (colour_lost) {
    // Doubtful: the estimate stays where the target was last seen with confidence; the samples
    // spread further each frame until one scores again.
    ++lost_frames_;
    vx_ = vy_ = 0.0;
  } else {
    vx_ = mean.x - estimate_.x;
    vy_ = mean.y - estimate_.y;
    estimate_ = mean;
    lost_frames_ = 0;
  }
  out.box = boxOf(estimate_);
  out.confidence = confidence;

  // 4. Model update (eq. 29), gated by the confidence (and by the response's reliability when
  // unreliable_stops_learning); nothing is learnt while the whole-frame search runs.
  const bool learn = !colour_lost && !(config_.unreliable_stops_learning && out.unreliable) &&
                     !searching_ && confidence >= config_.update_min_score;
  if (learn && config_.learning_rate > 0.0) {
    std::vector<float> o, s;
    histograms(image, out.box, &o, &s);
    const float a = static_cast<float>(config_.learning_rate);
    for (int k = 0; k < nb; ++k) {
      h_object_[k] = (1.0f - a) * h_object_[k] + a * o[k];
      h_surround_[k] = (1.0f - a) * h_surround_[k] + a * s[k];
    }
    if (config_.distractor_ratio > 0.0) learnDistractors(image, out.box, lut);
    if (use_filter)
      filter_.update(grey_image, {estimate_.x, estimate_.y}, std::exp(estimate_.log_scale));
    if (use_scale_filter)
      scale_filter_.update(grey_image, {estimate_.x, estimate_.y}, out.box.size());
    if (use_template && config_.template_rate > 0.0) {
      const std::vector<float> p = patch(grey, out.search.tl(), out.box);
      if (!p.empty()) {
        const float r = static_cast<float>(config_.template_rate);
        double norm = 0.0;
        for (std::size_t k = 0; k < p.size(); ++k) {
          template_[k] = (1.0f - r) * template_[k] + r * p[k];
          norm += static_cast<double>(template_[k]) * template_[k];
        }
        const float inv = static_cast<float>(1.0 / std::sqrt(std::max(norm, 1e-12)));
        for (float& v : template_) v *= inv;
      }
    }
  }
  out.distractors = out_distractors_;
  out.samples.reserve(n);
  for (const Sample& s : samples_) out.samples.push_back(boxOf(s));
  out.weights = weights_;
  return out;
}

}  // namespace adaptive_perception::tracking
