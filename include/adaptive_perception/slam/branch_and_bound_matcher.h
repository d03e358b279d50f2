#pragma once
// A wide correlative search by branch and bound (Olson, ICRA 2009, section IV-B, multi-resolution
// search; Hess et al., "Real-time loop closure in 2D LIDAR SLAM", ICRA 2016, section V-C): the best
// pose of a scan in a likelihood field over a window too large to score pose by pose (tens of
// metres and tens of degrees, as after a long loop).
//
// The lattice: yaw in steps of yaw_step_rad within +-search_yaw_rad of the prior; for each yaw the
// scan's points rotated and placed at the prior, each rounded to its nearest cell, then shifted by
// whole cells (ox, oy), |ox|, |oy| <= floor(search_xy_m / resolution). A lattice pose's score is
// the mean over the points of the field's value at its cell (0 off the field): what matchScan's
// exhaustive stage computes, without the prior's pull.
//
// The bound: level d holds, at each cell, the largest field value of the 2^d x 2^d block of cells
// starting there; the score of an offset at level d is then at least that of every offset of its
// block. Offsets are tried at the coarsest level first, best bound first; a block whose bound is
// no better than the best score found so far (or than min_score) is dropped unseen. The result is
// the lattice's best pose, exactly what scoring every lattice pose gives (a unit test checks it
// against the exhaustive search), at a cost that depends on how many blocks look promising.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/slam/scan_matcher.h"

namespace adaptive_perception::slam {

struct BranchAndBoundWindow {
  double search_xy_m = 10.0;    // translation window half-width around the prior
  double search_yaw_rad = 0.5;  // rotation window half-width
  double yaw_step_rad = 0.01;
  // The time bound: once this many bounds have been computed (the top level's, one per top block
  // and yaw, always are), the search descends no further and returns the best pose found so far
  // (best bound first, so the likeliest blocks were tried first); 0: no bound, the lattice's best.
  long max_bounds = 0;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

/// Whether a match is ambiguous in rotation: some lattice pose turned more than half_width_rad
/// from the best scores more than ratio times the best's score (a square corridor seen turned by a
/// right angle). Answered by a second descent from the same top level, with the poses within the
/// band left out and the bar at ratio times the best: it stops at the first such pose.
struct RotationAmbiguity {
  double half_width_rad = 0.3;
  double ratio = 0.9;
};

class BranchAndBoundMatcher {
 public:
  /// Precomputes levels 0..depth of `field` (depth in [0, 12]; each level is a copy of the field,
  /// and a top block of about a quarter of the window prunes well). Keeps no reference to
  /// `field`.
  BranchAndBoundMatcher(const LikelihoodField& field, int depth);

  /// The best lattice pose of `points_robot` within the window around `prior` whose score is
  /// above min_score (within window.max_bounds: the best found before the budget ran out); nullopt
  /// when none is. `nodes_visited` (optional) counts the bounds computed.
  /// With `ambiguity` and a match found, *ambiguous says whether it is ambiguous in rotation
  /// (RotationAmbiguity; within the same max_bounds budget: a check the budget cut short counts
  /// as ambiguous).
  std::optional<ScanMatch> match(const std::vector<Eigen::Vector2d>& points_robot,
                                 const math::SE2& prior, const BranchAndBoundWindow& window,
                                 double min_score, long* nodes_visited = nullptr,
                                 const RotationAmbiguity* ambiguity = nullptr,
                                 bool* ambiguous = nullptr) const;

  int depth() const { return static_cast<int>(levels_.size()) - 1; }

 private:
  // levels_[d] has (rows + 2^d - 1) x (cols + 2^d - 1) cells; cell (x, y) of the field is at
  // (x + 2^d - 1, y + 2^d - 1), so that a block starting left of or above the field is stored too.
  std::vector<cv::Mat> levels_;
  Eigen::Vector2d origin_m_;
  double resolution_m_;
};

}  // namespace adaptive_perception::slam
