#pragma once
// Scoring extracted segments against the true walls in view (simulator ground truth), shared by
// evaluate_lines and the rostest.
//
// A true wall piece (a run of consecutive beams returning from one wall) counts for recall when the
// scan put at least min_points returns and min_length_m on it with a mean spacing within max_gap_m
// (a wall seen at a grazing angle is not one cluster). An extracted segment matches a piece when
// its endpoints lie within `max_offset_m` (mean) of the piece's line, the directions agree within
// `max_angle_rad`, and it overlaps the piece by at least half its own length. Endpoint error: mean
// distance of a matched segment's endpoints to the piece's ends. Line NEES: the error of a matched
// segment's (rho, alpha) against the piece's true line, squared in the metric of the fit
// covariance (2 degrees of freedom: near 2 when the covariance tells the truth).
#include <Eigen/Core>
#include <vector>

#include "adaptive_perception/laser/line_extraction.h"

namespace adaptive_perception::laser {

struct TrueWallPiece {
  Eigen::Vector2d start_m, end_m;  // in the scan's frame
  int hits = 0;
};

struct LineScore {
  long extracted = 0, extracted_matched = 0, truth_eligible = 0, truth_matched = 0, pairs = 0;
  double endpoint_error_sum_m = 0.0, angle_error_sum_rad = 0.0;
  double line_nees_sum = 0.0;
  long line_nees_in_bounds = 0;  // inside the 95% chi-square interval of 2 dof

  void add(const LineScore& o);
  double precision() const { return extracted ? double(extracted_matched) / extracted : 1.0; }
  double recall() const { return truth_eligible ? double(truth_matched) / truth_eligible : 1.0; }
  double meanEndpointError() const { return pairs ? endpoint_error_sum_m / pairs : 0.0; }
  double meanAngleErrorRad() const { return pairs ? angle_error_sum_rad / pairs : 0.0; }
  double meanLineNees() const { return pairs ? line_nees_sum / pairs : 0.0; }
  double lineNeesInBounds() const { return pairs ? double(line_nees_in_bounds) / pairs : 0.0; }
};

LineScore scoreSegments(const std::vector<LineSegment>& extracted,
                        const std::vector<TrueWallPiece>& truth, const LineExtractionConfig& config,
                        double max_offset_m = 0.1, double max_angle_rad = 0.0873);

}  // namespace adaptive_perception::laser
