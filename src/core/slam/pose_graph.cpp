#include "adaptive_perception/slam/pose_graph.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/symmetric2.h"
#include "adaptive_perception/slam/branch_and_bound_matcher.h"

namespace adaptive_perception::slam {

namespace {
void need(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("LoopClosingConfig: " + what);
}
}  // namespace

ScanMatcherConfig LoopClosingConfig::coarseMatcher() const {
  ScanMatcherConfig coarse;
  coarse.resolution_m = coarse_resolution_m;
  coarse.search_xy_m = coarse_search_xy_m;
  coarse.search_yaw_rad = coarse_search_yaw_rad;
  coarse.yaw_step_rad = coarse_yaw_step_rad;
  coarse.hit_std_m = 2.0 * fine.hit_std_m;
  return coarse;
}

void LoopClosingConfig::validate() const {
  need(std::isfinite(node_translation_m) && node_translation_m > 0.0,
       "node_translation_m must be > 0");
  need(std::isfinite(node_rotation_rad) && node_rotation_rad > 0.0,
       "node_rotation_rad must be > 0");
  for (double v :
       {odometry_std_m, odometry_std_rad, loop_std_m, chain_gate_std_m, chain_gate_std_rad})
    need(std::isfinite(v) && v > 0.0, "the *_std_* fields must be > 0");
  need(std::isfinite(chain_gate_chi2) && chain_gate_chi2 > 0.0, "chain_gate_chi2 must be > 0");
  need(std::isfinite(chain_huber_scale) && chain_huber_scale > 0.0,
       "chain_huber_scale must be > 0");
  need(std::isfinite(free_space_tolerance_m) && free_space_tolerance_m >= 0.0,
       "free_space_tolerance_m must be >= 0");
  need(std::isfinite(max_free_space_violations) && max_free_space_violations >= 0.0 &&
           max_free_space_violations <= 1.0,
       "max_free_space_violations must be in [0, 1]");
  need(min_node_gap >= 1, "min_node_gap must be >= 1");
  need(std::isfinite(search_radius_m) && search_radius_m >= 0.0, "search_radius_m must be >= 0");
  need(max_candidates_per_node >= 0, "max_candidates_per_node must be >= 0");
  need(submap_half_nodes >= 0, "submap_half_nodes must be >= 0");
  coarseMatcher().validate();
  fine.validate();
  need(std::isfinite(min_loop_score) && min_loop_score >= 0.0 && min_loop_score <= 1.0,
       "min_loop_score must be in [0, 1]");
  need(std::isfinite(max_range_m) && max_range_m > 0.1, "max_range_m must be > 0.1");
  need(wide_every_nodes >= 1, "wide_every_nodes must be >= 1");
  for (double v : {wide_sigmas, wide_drift_per_m, wide_confirm_m, wide_confirm_rad})
    need(std::isfinite(v) && v >= 0.0,
         "wide_sigmas, wide_drift_per_m and the wide_confirm_* fields must be >= 0");
  try {
    chain_noise.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("chain_noise: ") + e.what());
  }
  need(std::isfinite(wide_max_xy_m) && wide_max_xy_m >= 0.0 && wide_max_xy_m <= 200.0,
       "wide_max_xy_m must be in [0, 200]");
  need(wide_max_bounds >= 0, "wide_max_bounds must be >= 0");
  need(std::isfinite(wide_ambiguity_yaw_rad) && wide_ambiguity_yaw_rad >= 0.0 &&
           wide_ambiguity_yaw_rad <= M_PI,
       "wide_ambiguity_yaw_rad must be in [0, pi]");
  need(std::isfinite(wide_ambiguity_ratio) && wide_ambiguity_ratio >= 0.0 &&
           wide_ambiguity_ratio <= 1.0,
       "wide_ambiguity_ratio must be in [0, 1]");
  need(std::isfinite(wide_max_free_space_violations) && wide_max_free_space_violations >= 0.0 &&
           wide_max_free_space_violations <= 1.0,
       "wide_max_free_space_violations must be in [0, 1]");
  need(std::isfinite(wide_min_score) && wide_min_score >= 0.0 && wide_min_score <= 1.0,
       "wide_min_score must be in [0, 1]");
  need(wide_confirm_nodes >= 1, "wide_confirm_nodes must be >= 1");
  need(std::isfinite(wide_min_loop_m) && wide_min_loop_m >= 0.0, "wide_min_loop_m must be >= 0");
}

namespace {
/// A scan's farthest return per 1-degree bearing bin (-1: none), in its robot frame.
struct BearingRanges {
  static constexpr int kBins = 360;
  std::vector<float> range = std::vector<float>(kBins, -1.0f);
  static int bin(const Eigen::Vector2d& p) {
    const int b =
        static_cast<int>(std::floor((std::atan2(p.y(), p.x()) + M_PI) * kBins / (2.0 * M_PI)));
    return std::clamp(b, 0, kBins - 1);
  }
  explicit BearingRanges(const std::vector<Eigen::Vector2d>& scan) {
    for (const auto& p : scan) {
      float& r = range[bin(p)];
      r = std::max(r, static_cast<float>(p.norm()));
    }
  }
  /// 0: out of view (beyond max_range_m or no return at its bearing); 1: seen, not in front of the
  /// return; 2: in front of the return by more than tolerance_m + 5% of its range (seen through).
  int classify(const Eigen::Vector2d& q, double max_range_m, double tolerance_m) const {
    const double d = q.norm();
    if (d > max_range_m) return 0;
    const float r = range[bin(q)];
    if (r < 0.0f) return 0;
    return d < r - tolerance_m - 0.05 * r ? 2 : 1;
  }
};
}  // namespace

double freeSpaceViolationShare(const std::vector<Eigen::Vector2d>& scan_a,
                               const std::vector<Eigen::Vector2d>& scan_b, const math::SE2& b_in_a,
                               double max_range_m, double tolerance_m) {
  const BearingRanges view_a(scan_a), view_b(scan_b);
  auto share = [&](const BearingRanges& view, const std::vector<Eigen::Vector2d>& pts,
                   const math::SE2& to_view) {
    long seen = 0, through = 0;
    for (const auto& p : pts) {
      const int c = view.classify(to_view.transformPoint(p), max_range_m, tolerance_m);
      seen += c > 0;
      through += c == 2;
    }
    return seen > 0 ? static_cast<double>(through) / seen : 0.0;
  };
  return std::max(share(view_a, scan_b, b_in_a), share(view_b, scan_a, b_in_a.inverse()));
}

LoopClosingMapper::LoopClosingMapper(LoopClosingConfig config) : config_(config) {
  config_.validate();
}

void LoopClosingMapper::add(const std::vector<Eigen::Vector2d>& points_robot,
                            const math::SE2& local_pose, const math::SE2* reference_pose,
                            const Eigen::Matrix3d* step_covariance) {
  if (!scans_.empty()) {
    // The step's variance: the local estimator's noise model, or the given covariance where that
    // is larger (a non-finite one is ignored).
    const math::SE2 step = math::between(last_local_, local_pose);
    const Eigen::Vector2d sd = localization::motionNoiseStd(step, config_.chain_noise);
    double yaw_var = sd.y() * sd.y(), xy_var = 2.0 * sd.x() * sd.x();
    if (step_covariance && step_covariance->allFinite()) {
      yaw_var = std::max(yaw_var, (*step_covariance)(2, 2));
      xy_var = std::max(xy_var, (*step_covariance)(0, 0) + (*step_covariance)(1, 1));
    }
    pending_yaw_var_ += yaw_var;
    pending_xy_var_ += xy_var;
  }
  last_local_ = local_pose;
  bool new_node = nodes_.empty();
  if (!new_node) {
    const math::SE2 d = math::between(nodes_.back().local, local_pose);
    new_node = std::hypot(d.x_m, d.y_m) >= config_.node_translation_m ||
               std::fabs(d.yaw_rad) >= config_.node_rotation_rad;
  }
  if (new_node) {
    std::vector<Eigen::Vector2d> pts;
    const double r2 = config_.max_range_m * config_.max_range_m;
    for (const auto& p : points_robot)
      if (p.allFinite() && p.squaredNorm() <= r2) pts.push_back(p);
    if (nodes_.empty()) {
      graph_.addNode(local_pose);
    } else {
      const int prev = graph_.numNodes() - 1;
      math::SE2 z = math::between(nodes_.back().local, local_pose);
      if (reference_pose && nodes_.back().has_reference) {
        const math::SE2 zr = math::between(nodes_.back().reference, *reference_pose);
        const double dx = z.x_m - zr.x_m, dy = z.y_m - zr.y_m;
        const double dyaw = math::angleDiff(z.yaw_rad, zr.yaw_rad);
        const double chi2 =
            (dx * dx + dy * dy) / (config_.chain_gate_std_m * config_.chain_gate_std_m) +
            dyaw * dyaw / (config_.chain_gate_std_rad * config_.chain_gate_std_rad);
        if (chi2 > config_.chain_gate_chi2) {
          z = zr;
          ++chain_replaced_;
        }
      }
      graph_.addNode(graph_.node(prev) * z);
      Eigen::Matrix3d info = Eigen::Matrix3d::Zero();
      info(0, 0) = info(1, 1) = 1.0 / (config_.odometry_std_m * config_.odometry_std_m);
      info(2, 2) = 1.0 / (config_.odometry_std_rad * config_.odometry_std_rad);
      if (config_.robust_chain)
        graph_.addRobustChainEdge(prev, prev + 1, z, info, config_.chain_huber_scale);
      else
        graph_.addEdge(prev, prev + 1, z, info);
    }
    const double path_m = nodes_.empty() ? 0.0
                                         : nodes_.back().path_m +
                                               std::hypot(local_pose.x_m - nodes_.back().local.x_m,
                                                          local_pose.y_m - nodes_.back().local.y_m);
    NodeData node{local_pose, static_cast<int>(scans_.size()),
                  reference_pose ? *reference_pose : math::SE2(), reference_pose != nullptr,
                  std::move(pts), path_m};
    const Eigen::Vector2d p(local_pose.x_m, local_pose.y_m);
    if (!nodes_.empty()) {
      const NodeData& prev = nodes_.back();
      node.yaw_var = prev.yaw_var + pending_yaw_var_;
      node.yaw_var_p = prev.yaw_var_p + pending_yaw_var_ * p;
      node.yaw_var_pp = prev.yaw_var_pp + pending_yaw_var_ * p.squaredNorm();
      node.xy_var = prev.xy_var + pending_xy_var_;
    }
    pending_yaw_var_ = pending_xy_var_ = 0.0;
    nodes_.push_back(std::move(node));
    const int n = graph_.numNodes() - 1;
    if (tryLoop(n)) {
      graph_.optimize();
    } else if (config_.wide_search && n - last_wide_node_ >= config_.wide_every_nodes) {
      const auto start = std::chrono::steady_clock::now();
      if (tryWide(n)) graph_.optimize(100);  // a correction of metres: more iterations
      wide_seconds_ +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
  }
  scans_.push_back(
      {static_cast<int>(nodes_.size()) - 1, math::between(nodes_.back().local, local_pose)});
}

double LoopClosingMapper::freeSpaceShare(int n, const math::SE2& xk_inv, const math::SE2& n_in_k,
                                         const std::vector<int>& submap) const {
  // The share of the new scan's points (at the matched pose) that some scan of the submap saw
  // through, among those that one of them could see; and the share of the submap's points that the
  // new scan saw through, among those it could see. The larger counts.
  const std::vector<Eigen::Vector2d>& scan = nodes_[n].points;
  const BearingRanges n_view(scan);
  std::vector<int> n_state(scan.size(), 0);
  long sub_seen = 0, sub_through = 0;
  for (int m : submap) {
    const math::SE2 n_in_m = (xk_inv * graph_.node(m)).inverse() * n_in_k;
    const math::SE2 m_in_n = n_in_m.inverse();
    const BearingRanges m_view(nodes_[m].points);
    for (size_t i = 0; i < scan.size(); ++i)
      n_state[i] =
          std::max(n_state[i], m_view.classify(n_in_m.transformPoint(scan[i]), config_.max_range_m,
                                               config_.free_space_tolerance_m));
    for (const auto& p : nodes_[m].points) {
      const int c = n_view.classify(m_in_n.transformPoint(p), config_.max_range_m,
                                    config_.free_space_tolerance_m);
      sub_seen += c > 0;
      sub_through += c == 2;
    }
  }
  const long n_seen = std::count_if(n_state.begin(), n_state.end(), [](int c) { return c > 0; });
  const long n_through = std::count(n_state.begin(), n_state.end(), 2);
  return std::max(n_seen > 0 ? static_cast<double>(n_through) / n_seen : 0.0,
                  sub_seen > 0 ? static_cast<double>(sub_through) / sub_seen : 0.0);
}

std::optional<LoopClosingMapper::Verified> LoopClosingMapper::verify(
    int n, int k, const math::SE2& prior, const std::vector<int>& submap,
    double max_free_space_violations, bool coarse_search) {
  ++attempts_;
  // The submap in k's frame.
  std::vector<Eigen::Vector2d> sub;
  const math::SE2 xk_inv = graph_.node(k).inverse();
  for (int m : submap) {
    const math::SE2 rel = xk_inv * graph_.node(m);
    for (const auto& p : nodes_[m].points) sub.push_back(rel.transformPoint(p));
  }
  if (sub.size() < 50) return std::nullopt;
  const ScanMatcherConfig coarse = config_.coarseMatcher();
  try {
    ScanMatch c{prior, 0.0};
    if (coarse_search) {
      const LikelihoodField coarse_field(sub, coarse.resolution_m, coarse.hit_std_m,
                                         coarse.search_xy_m + 1.0, config_.connect_gap_m);
      c = matchScan(coarse_field, nodes_[n].points, prior, coarse);
    }
    const LikelihoodField fine_field(sub, config_.fine.resolution_m, config_.fine.hit_std_m,
                                     config_.fine.search_xy_m + 1.0, config_.connect_gap_m);
    const ScanMatch f = matchScan(fine_field, nodes_[n].points, c.pose, config_.fine);
    if (f.score < config_.min_loop_score) return std::nullopt;
    // The free-space check against k's own neighbours only: over a long stretch, people, doors and
    // the stretch's own drift put some point of the new scan in front of some scan's return.
    std::vector<int> near;
    for (int m : submap)
      if (std::abs(m - k) <= config_.submap_half_nodes) near.push_back(m);
    const double share = freeSpaceShare(n, xk_inv, f.pose, near);
    if (share > max_free_space_violations) {
      ++free_space_rejected_;
      return std::nullopt;
    }
    // The match's own information, scaled as a whole so that its best-seen translation has
    // loop_std_m: along a corridor the scan cannot see, the loop edge says next to nothing.
    Eigen::Matrix3d info = matchInformation(fine_field, nodes_[n].points, f.pose);
    const double best_xy = math::symmetricEigenvalues(info.topLeftCorner<2, 2>())[1];
    if (!(best_xy > 0.0)) return std::nullopt;
    info *= 1.0 / (config_.loop_std_m * config_.loop_std_m * best_xy);
    info += 1e-6 * Eigen::Matrix3d::Identity();  // positive definite for the solver
    return Verified{f.pose, info, f.score};
  } catch (const std::invalid_argument&) {
    return std::nullopt;  // a submap too large for a field: no match
  }
}

bool LoopClosingMapper::tryLoop(int n) {
  if (nodes_[n].points.size() < 20) return false;
  const math::SE2 xn = graph_.node(n);
  std::vector<std::pair<double, int>> cands;
  for (int k = 0; k + config_.min_node_gap <= n; ++k) {
    const math::SE2 xk = graph_.node(k);
    const double d = std::hypot(xk.x_m - xn.x_m, xk.y_m - xn.y_m);
    if (d <= config_.search_radius_m) cands.emplace_back(d, k);
  }
  std::sort(cands.begin(), cands.end());
  bool closed = false;
  int tried = 0;
  for (const auto& [d, k] : cands) {
    if (tried >= config_.max_candidates_per_node) break;
    ++tried;
    std::vector<int> submap;
    for (int m = std::max(0, k - config_.submap_half_nodes);
         m <= std::min(n - config_.min_node_gap, k + config_.submap_half_nodes); ++m)
      submap.push_back(m);
    const auto v = verify(n, k, graph_.node(k).inverse() * xn, submap,
                          config_.max_free_space_violations, true);
    if (!v) continue;
    graph_.addEdge(k, n, v->n_in_k, v->information, true);
    loop_edges_.push_back({nodes_[k].scan, nodes_[n].scan, v->n_in_k, v->score});
    closed = true;
  }
  return closed;
}

std::pair<double, double> LoopClosingMapper::accumulatedStd(int k, int n) const {
  const NodeData &a = nodes_[k], &b = nodes_[n];
  const Eigen::Vector2d pn(b.local.x_m, b.local.y_m);
  const double s0 = b.yaw_var - a.yaw_var;
  const double xy = (b.xy_var - a.xy_var) + s0 * pn.squaredNorm() -
                    2.0 * pn.dot(b.yaw_var_p - a.yaw_var_p) + (b.yaw_var_pp - a.yaw_var_pp);
  return {std::sqrt(std::max(0.0, s0)), std::sqrt(std::max(0.0, xy))};
}

bool LoopClosingMapper::tryWide(int n) {
  if (nodes_[n].points.size() < 20) return false;
  last_wide_node_ = n;
  if (wide_pending_ && n - wide_pending_->n > config_.wide_confirm_nodes) wide_pending_.reset();
  const math::SE2 xn = graph_.node(n);
  // The older nodes that could hold the scan, and the window.
  double window_m = 0.0, sigma_yaw = 0.0;
  std::vector<int> members;
  std::vector<std::pair<double, double>> member_window;  // r_k and its yaw window, m and rad
  for (int k = 0; k + config_.min_node_gap <= n; ++k) {
    const double along = nodes_[n].path_m - nodes_[k].path_m;
    if (along < config_.wide_min_loop_m) continue;
    const auto [s_yaw, s_xy] = accumulatedStd(k, n);
    const double r = std::min(config_.wide_max_xy_m, config_.search_radius_m +
                                                         config_.wide_drift_per_m * along +
                                                         config_.wide_sigmas * s_xy);
    const math::SE2 xk = graph_.node(k);
    if (std::hypot(xk.x_m - xn.x_m, xk.y_m - xn.y_m) > r + config_.max_range_m) continue;
    members.push_back(k);
    member_window.emplace_back(
        r, std::min(M_PI, config_.coarse_search_yaw_rad + config_.wide_sigmas * s_yaw));
    window_m = std::max(window_m, r);
    sigma_yaw = std::max(sigma_yaw, s_yaw);
  }
  if (members.size() < 2 || window_m <= config_.coarse_search_xy_m) return false;
  ++wide_attempts_;
  std::vector<Eigen::Vector2d> map;
  for (int k : members) {
    const math::SE2 xk = graph_.node(k);
    for (const auto& p : nodes_[k].points) map.push_back(xk.transformPoint(p));
  }
  BranchAndBoundWindow window;
  window.search_xy_m = window_m;
  window.search_yaw_rad =
      std::min(M_PI, config_.coarse_search_yaw_rad + config_.wide_sigmas * sigma_yaw);
  window.yaw_step_rad = config_.coarse_yaw_step_rad;
  window.max_bounds = config_.wide_max_bounds;
  std::optional<ScanMatch> wide;
  try {
    const ScanMatcherConfig coarse = config_.coarseMatcher();
    const LikelihoodField field(map, coarse.resolution_m, coarse.hit_std_m, 1.0,
                                config_.connect_gap_m);
    // Blocks of about a quarter of the window, at most 64 cells (each level is a copy of the
    // field; a finer top level costs fewer bytes than it costs bounds).
    const int cells = static_cast<int>(window_m / config_.coarse_resolution_m);
    int depth = 0;
    while (depth < 6 && (2 << depth) * 4 <= cells) ++depth;
    // At most kWidePoints of the scan's points, evenly spread: the proposal is matched again
    // with every point (verify).
    constexpr size_t kWidePoints = 180;
    const std::vector<Eigen::Vector2d>& scan = nodes_[n].points;
    std::vector<Eigen::Vector2d> sparse;
    const size_t stride = (scan.size() + kWidePoints - 1) / kWidePoints;
    for (size_t i = 0; i < scan.size(); i += stride) sparse.push_back(scan[i]);
    const BranchAndBoundMatcher bnb(field, depth);
    // Ambiguous in rotation (a square corridor seen turned by a right angle, a symmetric room):
    // some pose turned at least wide_ambiguity_yaw_rad from the best scores nearly as well.
    const RotationAmbiguity check{config_.wide_ambiguity_yaw_rad, config_.wide_ambiguity_ratio};
    const bool check_it = config_.wide_ambiguity_ratio > 0.0 &&
                          window.search_yaw_rad > config_.wide_ambiguity_yaw_rad;
    bool ambiguous = false;
    long visited = 0;
    wide = bnb.match(sparse, xn, window, config_.wide_min_score, &visited,
                     check_it ? &check : nullptr, &ambiguous);
    if (config_.wide_max_bounds > 0 && visited >= config_.wide_max_bounds) ++wide_budget_cut_;
    if (wide && ambiguous) {
      ++wide_ambiguous_;
      return false;
    }
  } catch (const std::invalid_argument&) {
    return false;  // the map is larger than a field may be
  }
  if (!wide) return false;
  // The local checks against the stretch of the chain around the member nearest the pose found,
  // as far as max_range_m along it either way (one traversal, so consistent in itself; a single
  // node's submap may have looked the other way along a corridor); the edge to that member.
  int k = -1;
  size_t k_index = 0;
  double best_d = 1e18;
  for (size_t i = 0; i < members.size(); ++i) {
    const math::SE2 xm = graph_.node(members[i]);
    const double d = std::hypot(xm.x_m - wide->pose.x_m, xm.y_m - wide->pose.y_m);
    if (d < best_d) {
      best_d = d;
      k = members[i];
      k_index = i;
    }
  }
  if (k < 0) return false;
  std::vector<int> submap;
  for (int m = k; m >= 0 && nodes_[k].path_m - nodes_[m].path_m <= config_.max_range_m; --m)
    submap.insert(submap.begin(), m);
  for (int m = k + 1; m + config_.min_node_gap <= n &&
                      nodes_[m].path_m - nodes_[k].path_m <= config_.max_range_m &&
                      nodes_[n].path_m - nodes_[m].path_m >= config_.wide_min_loop_m;
       ++m)
    submap.push_back(m);
  const math::SE2 xk = graph_.node(k);
  const auto v = verify(n, k, xk.inverse() * wide->pose, submap,
                        config_.wide_max_free_space_violations, false);
  if (!v) return false;
  // The search ran over the widest member's window; the loop found must lie within the window of
  // the member it joins (its own accumulated uncertainty): a recent member matched at the shift
  // only an older one could explain is a look-alike place, not a loop.
  const math::SE2 implied = xk * v->n_in_k;
  if (std::hypot(implied.x_m - xn.x_m, implied.y_m - xn.y_m) > member_window[k_index].first ||
      std::fabs(math::wrapAngle(implied.yaw_rad - xn.yaw_rad)) > member_window[k_index].second) {
    ++wide_beyond_window_;
    return false;
  }
  ++wide_matches_;
  const WideHypothesis h{n, k, *v, (xk * v->n_in_k) * xn.inverse()};
  if (wide_pending_) {
    // The two corrections agree within the tolerance plus the uncertainty accumulated between
    // the two nodes: both applied to this node's pose, they put it in the same place (compared
    // there, not as transforms about the map's origin, where a small turn between them would
    // read as a shift growing with the distance from the origin).
    const math::SE2 by_first = wide_pending_->correction * xn, by_second = h.correction * xn;
    const auto [s_yaw, s_xy] = accumulatedStd(wide_pending_->n, n);
    const double between_m = nodes_[n].path_m - nodes_[wide_pending_->n].path_m;
    if (std::hypot(by_first.x_m - by_second.x_m, by_first.y_m - by_second.y_m) <=
            config_.wide_confirm_m + config_.wide_drift_per_m * between_m +
                config_.wide_sigmas * s_xy &&
        std::fabs(math::wrapAngle(by_first.yaw_rad - by_second.yaw_rad)) <=
            config_.wide_confirm_rad + config_.wide_sigmas * s_yaw) {
      const WideHypothesis first = *wide_pending_;
      for (const WideHypothesis* e : {&first, &h}) {
        graph_.addEdge(e->k, e->n, e->match.n_in_k, e->match.information, true, false);
        loop_edges_.push_back(
            {nodes_[e->k].scan, nodes_[e->n].scan, e->match.n_in_k, e->match.score, true});
      }
      ++wide_confirmed_;
      wide_pending_.reset();
      return true;
    }
  }
  wide_pending_ = h;
  return false;
}

std::vector<math::SE2> LoopClosingMapper::trajectory() const {
  std::vector<math::SE2> out;
  out.reserve(scans_.size());
  for (const ScanRef& s : scans_) out.push_back(graph_.node(s.node) * s.offset);
  return out;
}

math::SE2 LoopClosingMapper::lastPose() const {
  if (scans_.empty()) return math::SE2();
  return graph_.node(scans_.back().node) * scans_.back().offset;
}

}  // namespace adaptive_perception::slam
