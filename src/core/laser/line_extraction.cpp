#include "adaptive_perception/laser/line_extraction.h"

#include <cmath>
#include <stdexcept>

namespace adaptive_perception::laser {

const config::Fields<LineExtractionConfig>& LineExtractionConfig::fields() {
  using C = LineExtractionConfig;
  using config::closed;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("min_range_m", &C::min_range_m, closed(0, 100),
               "returns closer than this (or the scan's range_min) are dropped (m)")
          .add("range_noise_std_m", &C::range_noise_std_m, config::Range{0, 1, false, true},
               "sigma_r: the breakpoint margin and the segments' covariance (m)")
          .add("bearing_noise_std_rad", &C::bearing_noise_std_rad,
               config::Range{0, 0.1, false, true}, "sigma_phi: the segments' covariance (rad)")
          .add("breakpoint_lambda_rad", &C::breakpoint_lambda_rad, closed(0.01, 1.4),
               "adaptive breakpoint detector (Borges & Aldon 2004): the shallowest incidence "
               "angle still taken as one surface (rad)")
          .add("max_gap_m", &C::max_gap_m, closed(0.01, 10),
               "consecutive returns farther apart always start a new cluster (m)")
          .add("split_threshold_m", &C::split_threshold_m, closed(0.001, 1),
               "Douglas-Peucker epsilon: the farthest-point distance that splits (m)")
          .add("merge_collinear", &C::merge_collinear,
               "merge neighbours whose union still fits within split_threshold_m")
          .add("min_points", &C::min_points, closed(2, 1000), "returns a segment needs")
          .add("min_length_m", &C::min_length_m, closed(0, 10),
               "length a segment needs between its projected endpoints (m)");
  return f;
}

void LineExtractionConfig::validate() const { fields().validate(*this); }

LineExtractor::LineExtractor(const LineExtractionConfig& config) { setConfig(config); }

void LineExtractor::setConfig(const LineExtractionConfig& config) {
  config.validate();
  config_ = config;
}

std::vector<LineSegment> LineExtractor::extract(const LaserScan2D& scan, ExtractionStats* stats) {
  ExtractionStats local;
  ExtractionStats* st = stats ? stats : &local;
  *st = ExtractionStats();
  st->beams = static_cast<int>(scan.ranges_m.size());
  validPoints(scan, config_.min_range_m, &points_);
  st->valid_points = static_cast<int>(points_.size());
  xy_.resize(points_.size());
  covs_.resize(points_.size());
  for (size_t i = 0; i < points_.size(); ++i) {
    xy_[i] = points_[i].p_m;
    covs_[i] = polarPointCovariance(points_[i].range_m, points_[i].bearing_rad,
                                    config_.range_noise_std_m, config_.bearing_noise_std_rad);
  }
  std::vector<LineSegment> out;
  // Adaptive breakpoint detector: consecutive returns farther apart than
  // r_prev sin(dphi) / sin(lambda - dphi) + 3 sigma_r (a surface seen at incidence lambda) start a
  // new cluster.
  int begin = 0;
  for (int k = 1; k <= static_cast<int>(points_.size()); ++k) {
    bool brk = k == static_cast<int>(points_.size());
    if (!brk) {
      const double dphi = std::fabs(points_[k].bearing_rad - points_[k - 1].bearing_rad);
      const double gap = (xy_[k] - xy_[k - 1]).norm();
      double d_max = config_.max_gap_m;
      if (dphi < config_.breakpoint_lambda_rad)
        d_max = std::min(d_max, points_[k - 1].range_m * std::sin(dphi) /
                                        std::sin(config_.breakpoint_lambda_rad - dphi) +
                                    3.0 * config_.range_noise_std_m);
      brk = gap > d_max;
    }
    if (brk) {
      ++st->clusters;
      processCluster(begin, k - 1, &out, st);
      begin = k;
    }
  }
  return out;
}

void LineExtractor::processCluster(int begin, int end, std::vector<LineSegment>* out,
                                   ExtractionStats* st) {
  const int m = end - begin + 1;
  if (m < config_.min_points) return;
  const std::vector<Eigen::Vector2d> pts(xy_.begin() + begin, xy_.begin() + end + 1);
  std::vector<int> v = simplifyPolyline(pts, config_.split_threshold_m, config_.split_method);
  // Merge: drop a shared vertex when the union of its two pieces still lies within the threshold of
  // the union's fitted line (collinear neighbours split by noise or by a gap-free breakpoint).
  if (config_.merge_collinear) {
    bool merged = true;
    while (merged && v.size() > 2) {
      merged = false;
      for (size_t k = 1; k + 1 < v.size(); ++k) {
        const PolarLine l = fitLine(pts, v[k - 1], v[k + 1], {});
        double worst = 0.0;
        for (int i = v[k - 1]; i <= v[k + 1]; ++i)
          worst = std::max(worst, std::fabs(lineDistance(l, pts[i])));
        if (worst <= config_.split_threshold_m) {
          v.erase(v.begin() + static_cast<long>(k));
          merged = true;
          break;
        }
      }
    }
  }
  const std::vector<Eigen::Matrix2d> covs(covs_.begin() + begin, covs_.begin() + end + 1);
  for (size_t k = 0; k + 1 < v.size(); ++k) {
    // A corner vertex is shared by both pieces in the split; each piece is fitted without the
    // vertex it shares with its successor, so no point is counted twice.
    const int first = v[k];
    const int last = (k + 2 < v.size()) ? v[k + 1] - 1 : v[k + 1];
    ++st->segments_before_filter;
    const int count = last - first + 1;
    if (count < config_.min_points) continue;
    LineSegment seg;
    seg.line = fitLine(pts, first, last, covs);
    seg.start_m = projectOnLine(seg.line, pts[first]);
    seg.end_m = projectOnLine(seg.line, pts[last]);
    seg.num_points = count;
    seg.first_beam = points_[begin + first].beam;
    seg.last_beam = points_[begin + last].beam;
    if (seg.length() < config_.min_length_m) continue;
    out->push_back(seg);
  }
}

}  // namespace adaptive_perception::laser
