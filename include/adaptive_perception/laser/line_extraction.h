#pragma once
// Wall segments from a laser scan: range filtering, breakpoint segmentation (adaptive breakpoint
// detector, Borges & Aldon 2004), split (Douglas-Peucker, Tables 1-2) and merge of collinear
// neighbours, total-least- squares fit in polar form with covariance, then minimum points / length
// checks.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/laser/line_fit.h"
#include "adaptive_perception/laser/polyline_split.h"
#include "adaptive_perception/laser/scan.h"

namespace adaptive_perception::laser {

struct LineExtractionConfig {
  double min_range_m = 0.05;  // returns closer than this (or the scan's range_min) are dropped
  double range_noise_std_m = 0.01;        // sigma_r: breakpoint margin and fit covariance
  double bearing_noise_std_rad = 0.0005;  // sigma_phi: fit covariance
  double breakpoint_lambda_rad =
      0.17;                // ABD: the shallowest incidence angle still one surface (~10 deg)
  double max_gap_m = 0.3;  // consecutive points farther apart always start a new cluster
  double split_threshold_m = 0.03;  // Douglas-Peucker epsilon: farthest-point distance that splits
  bool merge_collinear = true;      // merge neighbours whose union still fits within the threshold
  int min_points = 6;               // a segment needs this many returns ...
  double min_length_m = 0.3;        // ... and this length between its projected endpoints
  SplitMethod split_method = SplitMethod::kRecursive;

  /// The tunable fields (config/fields.h), split_method aside (an enum: parseSplitMethod).
  static const config::Fields<LineExtractionConfig>& fields();
  void validate() const;  // throws std::invalid_argument naming the field, value and allowed range
};

struct LineSegment {
  PolarLine line;                  // in the scan's frame
  Eigen::Vector2d start_m, end_m;  // first and last point projected onto the line
  int num_points = 0;
  int first_beam = 0, last_beam = 0;
  double length() const { return (end_m - start_m).norm(); }
};

struct ExtractionStats {
  int beams = 0, valid_points = 0, clusters = 0, segments_before_filter = 0;
};

/// Re-usable extractor (keeps its point buffers between scans).
class LineExtractor {
 public:
  explicit LineExtractor(const LineExtractionConfig& config = LineExtractionConfig());
  const LineExtractionConfig& config() const { return config_; }
  void setConfig(const LineExtractionConfig& config);
  std::vector<LineSegment> extract(const LaserScan2D& scan, ExtractionStats* stats = nullptr);

 private:
  void processCluster(int begin, int end, std::vector<LineSegment>* out, ExtractionStats* stats);
  LineExtractionConfig config_;
  std::vector<ScanPoint> points_;
  std::vector<Eigen::Vector2d> xy_;
  std::vector<Eigen::Matrix2d> covs_;
};

}  // namespace adaptive_perception::laser
