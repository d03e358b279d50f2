#pragma once
// Recursive polyline splitting (Douglas & Peucker 1973; the perception paper's Tables 1-2): split a
// run of points at the point farthest from the chord between its ends while that distance exceeds a
// threshold.
//
// Two implementations with the same output:
//   kRecursive  Table 2's linear scan for the farthest point: O(n^2) worst case, O(n log n)
//   typical. kHullTree   the farthest point from a line over an index range is an extreme point of
//   the range's convex
//               hull in the direction of the line's normal (the geometric idea of Hershberger &
//               Snoeyink's path hulls). A segment tree over the points stores the upper and lower
//               hull of each node; a query visits O(log n) nodes and binary-searches each hull:
//               O(log^2 n) per split, O(n log^2 n) worst case overall. (Hershberger-Snoeyink's path
//               hull gets O(n log n) with a more delicate structure; the hull tree keeps the same
//               output with far simpler code.) Ties in distance (exactly equal doubles) may be
//               broken differently; they do not occur in measured data.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "adaptive_perception/config/enum_names.h"

namespace adaptive_perception::laser {

enum class SplitMethod { kRecursive, kHullTree };
/// The split methods' words: "recursive", "hull_tree".
const config::EnumNames<SplitMethod>& splitMethods();
SplitMethod parseSplitMethod(const std::string& name);

/// The farthest point strictly between i and j from the line through points[i], points[j] (Table
/// 2): its index and distance; {-1, 0} when j <= i + 1.
struct FarthestPoint {
  int index = -1;
  double distance_m = 0.0;
};
FarthestPoint findFarthestLinear(const std::vector<Eigen::Vector2d>& points, int i, int j);

/// Farthest-point queries over index ranges in O(log^2 n) (see kHullTree above).
class HullTree {
 public:
  explicit HullTree(const std::vector<Eigen::Vector2d>& points);
  FarthestPoint findFarthest(int i, int j) const;

 private:
  struct Node {
    std::vector<int> upper, lower;  // hull vertex indices, sorted by x
  };
  void build(int node, int lo, int hi, std::vector<int>* sorted);
  void query(int node, int lo, int hi, int qlo, int qhi, const Eigen::Vector2d& n, double* best_max,
             int* arg_max, double* best_min, int* arg_min) const;
  static int extreme(const std::vector<int>& chain, const std::vector<Eigen::Vector2d>& pts,
                     const Eigen::Vector2d& dir);
  const std::vector<Eigen::Vector2d>& pts_;
  std::vector<Node> nodes_;
  int n_;
};

/// Vertex indices (into `points`, ascending, first 0 and last n-1) of the simplified polyline: runs
/// [v_k, v_k+1] are the line pieces. Empty input gives an empty result.
std::vector<int> simplifyPolyline(const std::vector<Eigen::Vector2d>& points, double threshold_m,
                                  SplitMethod method);

}  // namespace adaptive_perception::laser
