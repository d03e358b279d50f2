#include "adaptive_perception/tracking/condensation_tracker.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "adaptive_perception/math/particle_set.h"

namespace adaptive_perception::tracking {

DistributionState defaultNoiseSd() {
  DistributionState sd;
  sd << 0.02, 0.02, 0.02, 0.005, 0.005, 0.005, 0.03, 0.03;
  return sd;
}

Ar2Model defaultDynamics() {
  Ar2Model m = Ar2Model::constantVelocity(defaultNoiseSd());
  for (int k = 3; k < kStateDim; ++k) {
    m.a1(k, k) = 1.0;
    m.a0(k, k) = 0.0;
  }
  return m;
}

void CondensationConfig::validate() const {
  fields().validate(*this);
  quantizer.validate();
  snake.validate();
  auto need = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(what);
  };
  need(max_distribution_points >= 10 && max_distribution_points <= 1000000,
       "max_distribution_points must be in 10..1000000");
  need(min_bin_count >= 1, "min_bin_count must be >= 1");
  need(morph_radius_px >= 0 && morph_radius_px <= 20, "morph_radius_px must be in 0..20");
  need(mu_affine >= 0.0 && mu_area >= 0.0 && mu_quality >= 0.0, "mu_* must be >= 0");
  need(area_velocity >= 0.0 && area_velocity <= 2.0, "area_velocity must be in [0, 2]");
  need(euler_scale > 0.0, "euler_scale must be > 0");
  need(min_area_px > 0.0, "min_area_px must be > 0");
  need(refine_dilate_px >= 0 && refine_dilate_px <= 20, "refine_dilate_px must be in 0..20");
  need(canny_low > 0.0 && canny_high >= canny_low, "need 0 < canny_low <= canny_high");
  need(reacquire_blobs >= 1 && reacquire_blobs <= 50, "reacquire_blobs must be in 1..50");
  need(contour_margin_px >= 0.0, "contour_margin_px must be >= 0");
  need(anchor_rate >= 0.0 && anchor_rate <= 1.0, "anchor_rate must be in [0, 1]");
  need(max_stretch >= 1.0, "max_stretch must be >= 1");
  need(local_lost_frames >= 0, "local_lost_frames must be >= 0");
  need(dynamics.a1.allFinite() && dynamics.a0.allFinite() && dynamics.b.allFinite() &&
           dynamics.d.allFinite(),
       "dynamics must be finite");
}

// The connected components of one sample's segmentation inside the roi.
struct CondensationTracker::Blobs {
  cv::Mat labels, stats, centroids;
  int count = 0;     // including the background label 0
  cv::Point offset;  // roi top-left in the frame
};

CondensationTracker::CondensationTracker(CondensationConfig config, std::uint64_t seed)
    : config_(std::move(config)), rng_(seed) {
  config_.validate();
}

namespace {
cv::Mat disk(int r) { return cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * r + 1, 2 * r + 1}); }

DistributionState clampState(DistributionState s) {
  for (int k = 3; k < 6; ++k) s[k] = std::max(1e-3, s[k]);
  for (int k = 6; k < 8; ++k) s[k] = std::clamp(s[k], -M_PI / 2, M_PI / 2);
  return s;
}
}  // namespace

void CondensationTracker::segment(const cv::Mat& roi_bins, const DistributionState& s,
                                  cv::Mat* seg) const {
  const ColorPoints warped = warpDistribution(reference_, reference_stats_, s);
  std::vector<int> count(config_.quantizer.size(), 0);
  for (const auto& p : warped) ++count[config_.quantizer.binOf(p)];
  std::vector<uchar> lut(count.size());
  for (size_t i = 0; i < count.size(); ++i) lut[i] = count[i] >= config_.min_bin_count ? 255 : 0;
  seg->create(roi_bins.size(), CV_8U);
  for (int r = 0; r < roi_bins.rows; ++r) {
    const int* b = roi_bins.ptr<int>(r);
    uchar* o = seg->ptr<uchar>(r);
    for (int c = 0; c < roi_bins.cols; ++c) o[c] = lut[b[c]];
  }
  if (config_.morph_radius_px > 0) {
    const cv::Mat k = disk(config_.morph_radius_px);
    cv::morphologyEx(*seg, *seg, cv::MORPH_OPEN, k);
    cv::morphologyEx(*seg, *seg, cv::MORPH_CLOSE, k);
  }
}

SampleScore CondensationTracker::score(const Blobs& blobs, const Contour& start, int label,
                                       double predicted_area, cv::Mat* boundary,
                                       cv::Point* boundary_offset) const {
  SampleScore out;
  const int* st = blobs.stats.ptr<int>(label);
  // The blob in its bounding box with one pixel of background around it.
  const cv::Rect box(st[cv::CC_STAT_LEFT] - 1, st[cv::CC_STAT_TOP] - 1, st[cv::CC_STAT_WIDTH] + 2,
                     st[cv::CC_STAT_HEIGHT] + 2);
  cv::Mat blob = cv::Mat::zeros(box.size(), CV_8U);
  for (int y = 1; y < box.height - 1; ++y) {
    const int* l = blobs.labels.ptr<int>(box.y + y) + box.x;
    uchar* o = blob.ptr<uchar>(y);
    for (int x = 1; x < box.width - 1; ++x) o[x] = l[x] == label ? 255 : 0;
  }
  cv::Mat eroded, edge;
  cv::erode(blob, eroded, cv::Mat());
  cv::subtract(blob, eroded, edge);
  const cv::Point offset = blobs.offset + box.tl();
  const AffineSnakeFit fit = fitAffineSnake(start, edge, offset, config_.snake);
  out.contour = fit.contour;
  out.phi_affine = fit.on_edge;
  out.area_px = contourArea(fit.contour);
  const double m = std::max(predicted_area, out.area_px);
  out.phi_area = m > 0.0 ? 1.0 - std::abs(predicted_area - out.area_px) / m : 0.0;
  out.euler = eulerNumber(blob);
  out.phi_quality = std::max(0.0, 1.0 - std::abs(out.euler - 1) / config_.euler_scale);
  if (out.area_px < config_.min_area_px) out.phi_area = 0.0;
  const double rho = config_.mu_affine * (1.0 - out.phi_affine) +
                     config_.mu_area * (1.0 - out.phi_area) +
                     config_.mu_quality * (1.0 - out.phi_quality);
  out.weight = std::exp(-rho * rho / (2.0 * config_.sigma * config_.sigma));
  if (boundary) {
    *boundary = edge;
    *boundary_offset = offset;
  }
  return out;
}

void CondensationTracker::setReference(const cv::Mat& bgr8, const Contour& c) {
  const cv::Rect frame(0, 0, bgr8.cols, bgr8.rows);
  const cv::Rect box = cv::Rect(contourBox(c)) & frame;
  if (box.area() <= 0) return;
  cv::Mat mask = contourMask(c, box.size(), box.tl());
  const int margin = static_cast<int>(std::lround(config_.contour_margin_px));
  if (margin > 0) {
    cv::Mat inner;
    cv::erode(mask, inner, disk(margin));
    if (cv::countNonZero(inner) >= 10) mask = inner;
  }
  const int inside = cv::countNonZero(mask);
  if (inside < 3) return;
  const int stride =
      std::max(1, (inside + config_.max_distribution_points - 1) / config_.max_distribution_points);
  ColorPoints pts;
  int k = 0;
  for (int y = 0; y < box.height; ++y) {
    const uchar* m = mask.ptr<uchar>(y);
    const cv::Vec3b* p = bgr8.ptr<cv::Vec3b>(box.y + y) + box.x;
    for (int x = 0; x < box.width; ++x)
      if (m[x] && (k++ % stride) == 0) pts.push_back(toColorSpace(p[x], config_.quantizer.space));
  }
  reference_ = std::move(pts);
  reference_stats_ = colorStats(reference_);
}

void CondensationTracker::init(const cv::Mat& bgr8, const cv::Rect& roi) {
  if (bgr8.type() != CV_8UC3 || bgr8.empty())
    throw std::invalid_argument("CondensationTracker::init expects a bgr8 image");
  const cv::Rect frame(0, 0, bgr8.cols, bgr8.rows);
  const cv::Rect r = roi & frame;
  if (r.width < 4 || r.height < 4)
    throw std::invalid_argument("initial region of interest is empty or outside the image");
  // C_0: the ellipse inscribed in the region, shrunk a little to keep the background out.
  const Contour ell = ellipseContour(r.x + r.width / 2.0, r.y + r.height / 2.0, 0.4 * r.width,
                                     0.4 * r.height, config_.contour_points);
  reference_.clear();
  const double saved_margin = config_.contour_margin_px;
  config_.contour_margin_px = 0.0;
  setReference(bgr8, ell);
  config_.contour_margin_px = saved_margin;
  if (reference_.empty())
    throw std::invalid_argument("initial region of interest holds too few pixels");
  // The contour: the boundary of the blob C_0 segments, around the region.
  contour_ = ellipseContour(r.x + r.width / 2.0, r.y + r.height / 2.0, r.width / 2.0,
                            r.height / 2.0, config_.contour_points);
  const cv::Mat bins = config_.quantizer.binImage(bgr8);
  const int mx = r.width / 2, my = r.height / 2;
  const cv::Rect search = cv::Rect(r.x - mx, r.y - my, r.width + 2 * mx, r.height + 2 * my) & frame;
  cv::Mat seg;
  segment(bins(search), stateOf(reference_stats_), &seg);
  cv::Mat labels;
  const int n = cv::connectedComponents(seg, labels, 8, CV_32S);
  std::vector<int> overlap(n, 0);
  const cv::Mat inside = contourMask(ell, search.size(), search.tl());
  for (int y = 0; y < search.height; ++y)
    for (int x = 0; x < search.width; ++x)
      if (inside.at<uchar>(y, x)) ++overlap[labels.at<int>(y, x)];
  int best = 0;
  for (int l = 1; l < n; ++l)
    if (overlap[l] > overlap[best] || best == 0) best = overlap[l] > 0 ? l : best;
  if (best > 0) {
    cv::Mat blob = labels == best;
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(blob, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE, search.tl());
    const auto largest = std::max_element(
        contours.begin(), contours.end(),
        [](const auto& a, const auto& b) { return cv::contourArea(a) < cv::contourArea(b); });
    // A blob much larger than the region leaks into similar-coloured surroundings: keep the
    // region's ellipse then.
    if (largest != contours.end() && largest->size() >= 3 &&
        cv::contourArea(*largest) >= config_.min_area_px &&
        cv::contourArea(*largest) <= 1.5 * contourArea(contour_))
      contour_ = resampleContour(*largest, config_.contour_points);
  }
  setReference(bgr8, contour_);
  area1_ = area2_ = contourArea(contour_);
  velocity_.setZero();
  lost_ = false;
  const DistributionState s0 = stateOf(reference_stats_);
  samples_.assign(config_.samples, s0);
  previous_ = samples_;
  weights_.assign(config_.samples, 1.0 / config_.samples);
}

TrackingResult CondensationTracker::track(const cv::Mat& bgr8) {
  if (!initialized()) throw std::logic_error("CondensationTracker::track before init");
  if (bgr8.type() != CV_8UC3 || bgr8.empty())
    throw std::invalid_argument("CondensationTracker::track expects a bgr8 image");
  const cv::Rect frame(0, 0, bgr8.cols, bgr8.rows);
  const cv::Mat bins = config_.quantizer.binImage(bgr8);

  // Prediction of the contour and its area.
  Contour predicted = contour_;
  if (!lost_)
    for (auto& p : predicted) p += velocity_;
  const double predicted_area =
      std::max(config_.min_area_px, area1_ + config_.area_velocity * (area1_ - area2_));
  // Lost for a few frames: a growing region around the last contour; then the whole frame.
  const bool global = lost_ && lost_count_ > config_.local_lost_frames;
  cv::Rect roi = frame;
  if (!global) {
    const cv::Rect2d b = contourBox(predicted);
    const double margin = config_.roi_margin * (1 + lost_count_);
    roi = cv::Rect(cv::Rect2d(b.x - margin * b.width, b.y - margin * b.height,
                              b.width * (1 + 2 * margin), b.height * (1 + 2 * margin))) &
          frame;
    if (roi.area() <= 0) roi = frame;
  }
  const cv::Mat roi_bins = bins(roi);
  const cv::Mat predicted_mask = contourMask(predicted, roi.size(), roi.tl());

  // Factored sampling and propagation.
  const auto parents =
      math::resampleIndices(weights_, samples_.size(), math::ResamplingScheme::kMultinomial, rng_);
  std::vector<DistributionState> next(samples_.size()), prev(samples_.size());
  for (size_t i = 0; i < parents.size(); ++i) {
    prev[i] = samples_[parents[i]];
    next[i] =
        clampState(config_.dynamics.sample(samples_[parents[i]], previous_[parents[i]], rng_));
  }

  // Measurement.
  std::vector<SampleScore> scores(next.size());
  cv::Mat seg;
  Blobs blobs;
  blobs.offset = roi.tl();
  auto candidates = [&](std::vector<std::pair<int, Contour>>* out) {
    out->clear();
    if (!global) {
      std::vector<int> overlap(blobs.count, 0);
      for (int y = 0; y < roi.height; ++y) {
        const uchar* m = predicted_mask.ptr<uchar>(y);
        const int* l = blobs.labels.ptr<int>(y);
        for (int x = 0; x < roi.width; ++x)
          if (m[x]) ++overlap[l[x]];
      }
      int best = 0;
      for (int l = 1; l < blobs.count; ++l)
        if (overlap[l] > overlap[best]) best = l;
      if (best > 0 && overlap[best] > 0) out->emplace_back(best, predicted);
      return;
    }
    // Lost: the largest blobs, the last contour moved and scaled onto each.
    std::vector<int> order(std::max(0, blobs.count - 1));
    std::iota(order.begin(), order.end(), 1);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return blobs.stats.at<int>(a, cv::CC_STAT_AREA) > blobs.stats.at<int>(b, cv::CC_STAT_AREA);
    });
    const cv::Rect2d cb = contourBox(contour_);
    const Eigen::Vector2d cc(cb.x + cb.width / 2, cb.y + cb.height / 2);
    for (int k = 0; k < std::min<int>(config_.reacquire_blobs, order.size()); ++k) {
      const int* st = blobs.stats.ptr<int>(order[k]);
      if (st[cv::CC_STAT_AREA] < config_.min_area_px) break;
      const double sx = st[cv::CC_STAT_WIDTH] / std::max(1.0, cb.width);
      const double sy = st[cv::CC_STAT_HEIGHT] / std::max(1.0, cb.height);
      const Eigen::Vector2d bc(roi.x + st[cv::CC_STAT_LEFT] + st[cv::CC_STAT_WIDTH] / 2.0,
                               roi.y + st[cv::CC_STAT_TOP] + st[cv::CC_STAT_HEIGHT] / 2.0);
      Contour c = contour_;
      for (auto& p : c) p = bc + Eigen::Vector2d(sx * (p.x() - cc.x()), sy * (p.y() - cc.y()));
      out->emplace_back(order[k], std::move(c));
    }
  };
  std::vector<std::pair<int, Contour>> cands;
  const double area_for_lost = std::max(config_.min_area_px, area1_);
  for (size_t i = 0; i < next.size(); ++i) {
    segment(roi_bins, next[i], &seg);
    blobs.count = cv::connectedComponentsWithStats(seg, blobs.labels, blobs.stats, blobs.centroids,
                                                   8, CV_32S);
    candidates(&cands);
    for (const auto& [label, start] : cands) {
      const SampleScore s =
          score(blobs, start, label, lost_ ? area_for_lost : predicted_area, nullptr, nullptr);
      if (s.weight > scores[i].weight) scores[i] = s;
    }
  }
  size_t best = 0;
  for (size_t i = 1; i < scores.size(); ++i)
    if (scores[i].weight > scores[best].weight) best = i;

  TrackingResult out;
  out.roi = roi;
  out.best = scores[best];
  out.state = next[best];
  out.segmentation = cv::Mat::zeros(bgr8.size(), CV_8U);
  // The best sample again, keeping its segmentation and boundary for the refinement.
  segment(roi_bins, next[best], &seg);
  seg.copyTo(out.segmentation(roi));
  const bool found = scores[best].weight >= config_.lost_weight && scores[best].contour.size() >= 3;
  if (found) {
    blobs.count = cv::connectedComponentsWithStats(seg, blobs.labels, blobs.stats, blobs.centroids,
                                                   8, CV_32S);
    candidates(&cands);
    cv::Mat boundary;
    cv::Point boundary_offset;
    Contour refined = scores[best].contour;
    for (const auto& [label, start] : cands) {
      const SampleScore s = score(blobs, start, label, lost_ ? area_for_lost : predicted_area,
                                  &boundary, &boundary_offset);
      if (std::abs(s.weight - scores[best].weight) > 1e-12) continue;
      // grad I* = Canny(I) masked by the dilated boundary of the best blob.
      const int pad = config_.refine_dilate_px + 1;
      const cv::Rect area = cv::Rect(boundary_offset.x - pad, boundary_offset.y - pad,
                                     boundary.cols + 2 * pad, boundary.rows + 2 * pad) &
                            frame;
      cv::Mat grey, edges, mask = cv::Mat::zeros(area.size(), CV_8U);
      cv::cvtColor(bgr8(area), grey, cv::COLOR_BGR2GRAY);
      cv::Canny(grey, edges, config_.canny_low, config_.canny_high, 3, true);
      const cv::Rect in_area(boundary_offset - area.tl(), boundary.size());
      const cv::Rect clipped = in_area & cv::Rect(0, 0, area.width, area.height);
      boundary(cv::Rect(clipped.tl() - in_area.tl(), clipped.size())).copyTo(mask(clipped));
      if (config_.refine_dilate_px > 0) cv::dilate(mask, mask, disk(config_.refine_dilate_px));
      cv::bitwise_and(edges, mask, edges);
      const AffineSnakeFit fit = fitAffineSnake(refined, edges, area.tl(), config_.snake);
      if (fit.matched >= static_cast<int>(refined.size()) / 2 &&
          fit.on_edge >= 0.5 * scores[best].phi_affine)
        refined = fit.contour;
      break;
    }
    // After a loss the old contour says nothing about the motion.
    velocity_ = lost_ ? Eigen::Vector2d::Zero()
                      : Eigen::Vector2d(contourCentroid(refined) - contourCentroid(contour_));
    contour_ = refined;
    area2_ = area1_;
    area1_ = std::max(config_.min_area_px, contourArea(contour_));
    setReference(bgr8, contour_);
  } else {
    velocity_.setZero();
  }
  lost_ = !found;
  lost_count_ = lost_ ? lost_count_ + 1 : 0;
  out.lost = lost_;

  // The new weighted set.
  std::vector<double> w(scores.size());
  double total = 0.0;
  for (size_t i = 0; i < scores.size(); ++i) total += (w[i] = scores[i].weight);
  if (total <= 0.0)
    w.assign(w.size(), 1.0 / w.size());
  else
    for (double& v : w) v /= total;
  {
    // Pull m and lambda towards the measured C_t (the last one while lost, so the samples do not
    // drift away from the appearance to re-acquire), moving the previous state alike (velocity
    // kept), and keep lambda within max_stretch of C_t's.
    const DistributionState target = stateOf(reference_stats_);
    for (size_t i = 0; i < next.size(); ++i) {
      DistributionState shift = DistributionState::Zero();
      shift.head<6>() = config_.anchor_rate * (target.head<6>() - next[i].head<6>());
      for (int k = 3; k < 6; ++k) {
        const double moved = next[i][k] + shift[k];
        shift[k] +=
            std::clamp(moved, target[k] / config_.max_stretch, target[k] * config_.max_stretch) -
            moved;
      }
      next[i] += shift;
      prev[i] += shift;
    }
  }
  samples_ = next;
  previous_ = prev;
  weights_ = w;
  out.samples = samples_;
  out.weights = weights_;
  out.sample_contours.reserve(scores.size());
  for (auto& s : scores) out.sample_contours.push_back(std::move(s.contour));
  out.contour = contour_;
  out.box = contourBox(contour_);
  std::vector<cv::Point2f> pts;
  for (const auto& p : contour_)
    pts.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  out.ellipse = pts.size() >= 5 ? cv::fitEllipse(pts) : cv::RotatedRect();
  out.distribution = reference_stats_;
  return out;
}

}  // namespace adaptive_perception::tracking
