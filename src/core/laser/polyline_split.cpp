#include "adaptive_perception/laser/polyline_split.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "adaptive_perception/config/enum_names.h"

namespace adaptive_perception::laser {

const config::EnumNames<SplitMethod>& splitMethods() {
  static const config::EnumNames<SplitMethod> names(
      "split_method",
      {{SplitMethod::kRecursive, "recursive"}, {SplitMethod::kHullTree, "hull_tree"}});
  return names;
}

SplitMethod parseSplitMethod(const std::string& name) { return splitMethods().parse(name); }

namespace {
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}
}  // namespace

FarthestPoint findFarthestLinear(const std::vector<Eigen::Vector2d>& v, int i, int j) {
  FarthestPoint f;
  if (j <= i + 1) return f;
  const Eigen::Vector2d d = v[j] - v[i];
  const double len = d.norm();
  double best = -1.0;
  for (int k = i + 1; k < j; ++k) {
    // Table 2: |det(v_i, v_j, v_k)| in homogeneous coordinates = |cross(v_j - v_i, v_k - v_i)|.
    const double c = std::fabs(cross(d, v[k] - v[i]));
    if (c > best) {
      best = c;
      f.index = k;
    }
  }
  f.distance_m = len > 0.0 ? best / len : (v[f.index] - v[i]).norm();
  return f;
}

HullTree::HullTree(const std::vector<Eigen::Vector2d>& points)
    : pts_(points), n_(static_cast<int>(points.size())) {
  if (n_ == 0) return;
  nodes_.resize(4 * n_);
  std::vector<int> sorted;
  build(1, 0, n_ - 1, &sorted);
}

void HullTree::build(int node, int lo, int hi, std::vector<int>* sorted) {
  // `sorted` returns the node's indices sorted by (x, y): merge sort up the tree.
  if (lo == hi) {
    sorted->assign(1, lo);
  } else {
    const int mid = (lo + hi) / 2;
    std::vector<int> left, right;
    build(2 * node, lo, mid, &left);
    build(2 * node + 1, mid + 1, hi, &right);
    sorted->resize(left.size() + right.size());
    std::merge(left.begin(), left.end(), right.begin(), right.end(), sorted->begin(),
               [this](int a, int b) {
                 return pts_[a].x() < pts_[b].x() ||
                        (pts_[a].x() == pts_[b].x() && pts_[a].y() < pts_[b].y());
               });
  }
  // Andrew's monotone chain.
  Node& nd = nodes_[node];
  for (int idx : *sorted) {
    while (nd.lower.size() >= 2 &&
           cross(pts_[nd.lower.back()] - pts_[nd.lower[nd.lower.size() - 2]],
                 pts_[idx] - pts_[nd.lower[nd.lower.size() - 2]]) <= 0)
      nd.lower.pop_back();
    nd.lower.push_back(idx);
    while (nd.upper.size() >= 2 &&
           cross(pts_[nd.upper.back()] - pts_[nd.upper[nd.upper.size() - 2]],
                 pts_[idx] - pts_[nd.upper[nd.upper.size() - 2]]) >= 0)
      nd.upper.pop_back();
    nd.upper.push_back(idx);
  }
}

// The vertex of a monotone (x-sorted) hull chain maximising dir . p. Along the upper chain (for
// dir.y >= 0) or the lower chain (dir.y <= 0) the dot product rises then falls: binary search for
// the first edge along which it stops rising.
int HullTree::extreme(const std::vector<int>& chain, const std::vector<Eigen::Vector2d>& pts,
                      const Eigen::Vector2d& dir) {
  int lo = 0, hi = static_cast<int>(chain.size()) - 1;
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (dir.dot(pts[chain[mid + 1]] - pts[chain[mid]]) > 0.0) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return chain[lo];
}

void HullTree::query(int node, int lo, int hi, int qlo, int qhi, const Eigen::Vector2d& n,
                     double* best_max, int* arg_max, double* best_min, int* arg_min) const {
  if (qhi < lo || hi < qlo) return;
  if (qlo <= lo && hi <= qhi) {
    const Node& nd = nodes_[node];
    // max n.p on the upper chain when n points up, else on the lower chain; min n.p = -max (-n).p.
    const int a = extreme(n.y() >= 0.0 ? nd.upper : nd.lower, pts_, n);
    const int b = extreme(n.y() >= 0.0 ? nd.lower : nd.upper, pts_, -n);
    const double va = n.dot(pts_[a]), vb = n.dot(pts_[b]);
    if (va > *best_max || (va == *best_max && a < *arg_max)) {
      *best_max = va;
      *arg_max = a;
    }
    if (vb < *best_min || (vb == *best_min && b < *arg_min)) {
      *best_min = vb;
      *arg_min = b;
    }
    return;
  }
  const int mid = (lo + hi) / 2;
  query(2 * node, lo, mid, qlo, qhi, n, best_max, arg_max, best_min, arg_min);
  query(2 * node + 1, mid + 1, hi, qlo, qhi, n, best_max, arg_max, best_min, arg_min);
}

FarthestPoint HullTree::findFarthest(int i, int j) const {
  FarthestPoint f;
  if (j <= i + 1) return f;
  const Eigen::Vector2d d = pts_[j] - pts_[i];
  const double len = d.norm();
  if (len == 0.0) return findFarthestLinear(pts_, i, j);  // degenerate chord: distance to a point
  const Eigen::Vector2d n(-d.y(), d.x());                 // |cross(d, p - v_i)| = |n . (p - v_i)|
  double best_max = -std::numeric_limits<double>::infinity(),
         best_min = std::numeric_limits<double>::infinity();
  int arg_max = std::numeric_limits<int>::max(), arg_min = std::numeric_limits<int>::max();
  query(1, 0, n_ - 1, i + 1, j - 1, n, &best_max, &arg_max, &best_min, &arg_min);
  const double base = n.dot(pts_[i]);
  const double up = best_max - base, down = base - best_min;
  // Same tie-break as the linear scan: the lower index wins on equal distance.
  if (up > down || (up == down && arg_max < arg_min)) {
    f.index = arg_max;
    f.distance_m = std::fabs(up) / len;
  } else {
    f.index = arg_min;
    f.distance_m = std::fabs(down) / len;
  }
  return f;
}

std::vector<int> simplifyPolyline(const std::vector<Eigen::Vector2d>& points, double threshold,
                                  SplitMethod method) {
  const int n = static_cast<int>(points.size());
  if (n == 0) return {};
  if (n == 1) return {0};
  std::vector<int> vertices{0};
  std::unique_ptr<HullTree> tree;
  if (method == SplitMethod::kHullTree) tree = std::make_unique<HullTree>(points);
  // Table 1, with an explicit stack (left part first) so deep recursions cannot overflow.
  std::vector<std::pair<int, int>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const FarthestPoint f = tree ? tree->findFarthest(i, j) : findFarthestLinear(points, i, j);
    if (f.index >= 0 && f.distance_m > threshold) {
      stack.push_back({f.index, j});
      stack.push_back({i, f.index});
    } else {
      vertices.push_back(j);
    }
  }
  return vertices;
}

}  // namespace adaptive_perception::laser
