#pragma once
// Loop closing for the line-landmark EKF: a pose graph over keyframes (Lu and Milios 1997; the
// graph-mapping column of Kuemmerle et al. 2009), optimised with Ceres.
//
// PoseGraph2D: nodes are SE(2) poses, edges relative poses z_ij = x_i^-1 x_j with an information
// matrix; the residual of an edge is sqrt(info) [R_i^T (t_j - t_i) - t_z; wrap(th_j - th_i -
// th_z)]; loop edges go through a Cauchy loss (a wrong loop closure is down-weighted rather than
// bending the whole map), chain edges through a Huber loss when robust_chain (a wrong chain edge,
// where the local estimator jumped and the gate let it through, is then undone by the loops that
// span it; Huber and not Cauchy, because Huber is convex: a loop's correction is still spread
// along the chain as least squares spreads it, never concentrated into one broken edge). Node 0
// is held fixed.
//
// LoopClosingMapper: takes every scan with its pose from the local estimator (the EKF over line
// landmarks driven by laser odometry); a scan becomes a graph node once the local pose moved
// node_translation_m or turned node_rotation_rad since the last node, the edge between
// consecutive nodes is the local estimator's relative pose, unless a second estimate of the motion
// is given (the laser-odometry front end's) and the two disagree beyond chain_gate_chi2: then the
// local estimator is taken to have jumped (a wrong line pairing turns the EKF's pose at once) and
// the edge is the second estimate's relative pose. Each new node is matched
// (scan_matcher.h: a coarse correlative search at coarse_resolution_m over a wide window, then the
// fine matcher) against the submap of each older node (at least min_node_gap nodes back) that
// lies within search_radius_m of its current estimate, nearest first, at most
// max_candidates_per_node; a match scoring at least min_loop_score adds a loop edge whose
// information is the match's own (scan_matcher.h, matchInformation; a corridor's length is not
// constrained), and the graph is optimised. A node that closes no loop so may close one by the
// wide search (LoopClosingConfig::wide_search), for loops the estimate has drifted metres from.
// Every scan's final pose is its last node's optimised pose composed with the local motion since
// that node.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "adaptive_perception/localization/motion_model.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/slam/scan_matcher.h"

namespace adaptive_perception::slam {

class PoseGraph2D {
 public:
  int addNode(const math::SE2& initial);
  /// Throws std::invalid_argument on an unknown node or a non-positive-definite information.
  /// A loop edge goes through the Cauchy loss unless `robust` is false (a loop already confirmed
  /// twice, whose residual before the optimisation may be hundreds of its stds).
  void addEdge(int i, int j, const math::SE2& z_ij, const Eigen::Matrix3d& information,
               bool loop = false, bool robust = true);
  /// A chain edge (not a loop) under the Huber loss with threshold huber_scale (in its standard
  /// deviations: the whitened residual's norm beyond which it counts linearly).
  void addRobustChainEdge(int i, int j, const math::SE2& z_ij, const Eigen::Matrix3d& information,
                          double huber_scale);
  /// Levenberg-Marquardt with a sparse Cholesky solver; returns the final cost.
  double optimize(int max_iterations = 30);
  int numNodes() const { return static_cast<int>(x_.size()); }
  int numEdges() const { return static_cast<int>(edges_.size()); }
  int numLoopEdges() const;
  math::SE2 node(int i) const;

 private:
  struct Edge {
    int i, j;
    math::SE2 z;
    Eigen::Matrix3d sqrt_info;
    bool loop;
    bool robust;
    double huber_scale = 0.0;  // > 0: a chain edge under the Huber loss
  };
  std::vector<std::array<double, 3>> x_;
  std::vector<Edge> edges_;
};

struct LoopClosingConfig {
  double node_translation_m = 0.5;  // a new graph node after this much motion
  double node_rotation_rad = 0.5;   // or this much turning
  double odometry_std_m = 0.02;     // per node edge: the local estimator's relative-pose std
  double odometry_std_rad = 0.01;
  // The chain edge's gate: the local estimator's and the front end's relative poses between two
  // nodes, their difference d scored as (dx^2 + dy^2) / chain_gate_std_m^2 + dyaw^2 /
  // chain_gate_std_rad^2. The stds are the disagreement of two sound estimates over one node
  // (on the three benchmark logs: 99% of node edges within 0.077 m and 3.2 degrees); 16.27 is the
  // 3-dof chi-square quantile at 99.9%, so with these stds a lone 4.6-degree or 0.12 m jump fails.
  double chain_gate_std_m = 0.03;
  double chain_gate_std_rad = 0.02;
  double chain_gate_chi2 = 16.27;
  // A chain edge the gate let through can still be wrong (a jump of the local estimator that the
  // front end shared): with robust_chain, chain edges go through a Huber loss whose threshold is
  // chain_huber_scale of their standard deviations (odometry_std_*), so that loops that span a
  // wrong one and are trusted as much as it (confirmed wide loops, which enter without the Cauchy
  // loss) pull it back. 1.345 is Huber's constant: 95% of least squares' efficiency when every
  // edge is sound. A loop under its Cauchy loss cannot undo a chain edge: each is discounted
  // alone (pose_graph_test's planted 3.6 m jump).
  bool robust_chain = true;
  double chain_huber_scale = 1.345;
  int min_node_gap = 20;         // nodes back along the chain before a node is a candidate
  double search_radius_m = 4.0;  // candidate nodes within this of the current estimate
  int max_candidates_per_node = 2;
  int submap_half_nodes = 4;         // a candidate's submap: its scan and this many either side
  double coarse_resolution_m = 0.1;  // the wide search
  double coarse_search_xy_m = 1.5;
  double coarse_search_yaw_rad = 0.5;
  double coarse_yaw_step_rad = 0.02;
  ScanMatcherConfig fine;        // then the fine match (its own window) at fine.resolution_m
  double min_loop_score = 0.55;  // of the fine match, 0..1
  // A match is also checked for free space: between the new scan at the matched pose and each
  // scan of the candidate's submap, a point of either more than free_space_tolerance_m (plus 5%
  // of the range) short of the other's return at its bearing is one the other saw through; a
  // match with more than max_free_space_violations of such points among those the other could
  // see is rejected (the walls of a wrong alignment stand in the other scans' free space; people
  // walking by make a few).
  double free_space_tolerance_m = 0.3;
  double max_free_space_violations = 0.1;
  double loop_std_m = 0.05;    // a loop edge's std in its best-seen direction (the others
                               // from the match's information, matchInformation)
  double max_range_m = 25.0;   // scan points farther than this are left out
  double connect_gap_m = 0.3;  // consecutive returns closer than this make one wall
  // The wide search, for a loop the estimate has drifted too far from for the window above (after a
  // kilometre of corridor the drift is tens of metres and degrees; a round hall, where the front
  // end keeps the odometry's heading, can turn the rest of the map by more than half a radian).
  // When a node closes no loop locally, at most every wide_every_nodes nodes, its scan is matched
  // by branch and bound (branch_and_bound_matcher.h, at coarse_resolution_m) against the scans of
  // every older node that could hold it. The window comes from the chain's accumulated uncertainty
  // since the candidate (see chain_noise): node k, at least wide_min_loop_m back along the chain,
  // with sigma_yaw(k) and sigma_xy(k) the accumulated heading and position stds of the new node
  // relative to k, is taken when it lies within r_k + max_range_m of the estimate, r_k =
  // search_radius_m + wide_drift_per_m * (the chain's length from k) + wide_sigmas * sigma_xy(k),
  // at most wide_max_xy_m; the window is the largest r_k taken, and in yaw coarse_search_yaw_rad +
  // wide_sigmas * the largest sigma_yaw(k), at most a full turn (pi either way); a match ambiguous
  // in rotation is dropped (wide_ambiguity_ratio), and so is one farther than r_k (a circle) or
  // k's own yaw window from the estimate, k the member nearest the match, the one it joins: one
  // search covers every member's window, but a member matched at a shift only an older one's
  // uncertainty allows is a look-alike place (a second wing of the same plan), not a loop. A
  // pose scoring at least wide_min_score is then matched and checked as a local candidate is
  // (min_loop_score), against the stretch of the chain
  // within max_range_m (along it) of the member nearest that pose: one traversal, consistent in
  // itself, which sees what the new scan sees even where the nearest node looked the other way
  // along a corridor. Its free-space check is against that node's own submap and allows
  // wide_max_free_space_violations: on fr-clinic, right matches (their walls drawn on the old ones
  // and looked at) had 0.06-0.53 of their points in front of some old return (people, doors,
  // halls), the wrong ones 0.09-1, most above 0.5: the check alone cannot tell them apart. So a
  // wide loop is believed only once a second one, found within wide_confirm_nodes nodes, moves the
  // estimate the same way (the two corrections put the second node within wide_confirm_m and
  // wide_confirm_rad of each other, plus wide_drift_per_m times and wide_sigmas of the chain's
  // accumulated uncertainty between the two nodes): evidence whose strength does not depend on
  // the window's size. Both edges then enter the graph without the robust loss, which would
  // otherwise discount a correction of hundreds of stds.
  bool wide_search = true;
  int wide_every_nodes = 8;  // every 4 nodes cost mit-csail 16% of its speed (28 -> 24x)
  // The accumulated uncertainty: each scan's motion since the one before adds the local
  // estimator's own prediction noise for it (chain_noise, in MotionModelConfig's terms; LaserSlam
  // sets it to the noise its EKF predicts with, measured on the benchmark relations), or the
  // step covariance given to add() where that is larger (the front end's, which along a
  // direction its scan match cannot see is the wheel odometry's). A node's heading variance
  // turns into position variance at every later node by its lever arm (the distance between
  // them), so sigma_xy grows with the building's size, not only with the path's length. The
  // model's per-step floors (min_*_std) add variance per scan even standing still, so the
  // uncertainty grows with the scan rate; with LaserSlam's noise that is 6e-8 rad^2 a scan. The
  // default here is the generic wheel-odometry model (MotionModelConfig's own defaults).
  localization::MotionModelConfig chain_noise;
  double wide_sigmas = 3.0;      // the window's half-width in accumulated stds
  // Plus, in translation, an allowance for drift that grows with the chain's length rather than
  // its square root (a bias). 0: the accumulated std already covers the drift seen (fr-clinic's
  // confirmed wide loop moved the estimate 6.6 m where 3 sigma_xy is 53 m; mit-csail's heading
  // drifted 0.16 rad where sigma_yaw is 0.24), and a term growing with the length widens every
  // window in a building whose corridors repeat (docs/slam_real_logs.md, 2026-12-06 night).
  double wide_drift_per_m = 0.0;
  double wide_max_xy_m = 60.0;   // the largest translation window: the cost bound (the
                                 // matched map's extent and the top level's size)
  // The time bound of one search (BranchAndBoundWindow::max_bounds): bounds computed, its top
  // level included (always computed), and the ambiguity check's descent after it; a check the
  // budget cuts short counts the match as ambiguous.
  long wide_max_bounds = 2000000;
  // A wide match is dropped when a pose turned more than wide_ambiguity_yaw_rad from it (in the
  // same window) scores more than wide_ambiguity_ratio of its score: a window of a full turn holds
  // the right angles of a square corridor and the half turn of a symmetric room, and two scans a
  // few metres apart agree on the same wrong turn, so agreement alone cannot keep it out. 0: no
  // such check.
  double wide_ambiguity_yaw_rad = 0.3;
  double wide_ambiguity_ratio = 0.9;
  double wide_min_score = 0.5;
  double wide_min_loop_m = 50.0;  // nearer nodes along the chain are left out: the scan sees
                                  // them still (2 max_range_m), and would match them best
  double wide_max_free_space_violations = 0.3;
  int wide_confirm_nodes = 20;
  double wide_confirm_m = 1.0;
  double wide_confirm_rad = 0.05;
  /// The coarse stage's matcher: coarse_* at twice the fine field's width (the local search's
  /// first stage, and the wide search's field).
  ScanMatcherConfig coarseMatcher() const;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

/// The free-space check of a match between two scans (points in their robot frames), B at
/// b_in_a in A's frame: the larger of the share of B's points that A saw through (more than
/// tolerance_m plus 5% of A's return short of it, at its bearing in 1-degree bins) among those
/// within A's returns' bearings and max_range_m, and the same for A's points against B. 0 for a
/// right match of a static scene; a wrong alignment puts walls where the other scan saw free space.
/// LoopClosingMapper applies it between the new scan and every scan of the candidate's submap
/// (a point counting as seen through when any of them saw through it).
double freeSpaceViolationShare(const std::vector<Eigen::Vector2d>& scan_a,
                               const std::vector<Eigen::Vector2d>& scan_b, const math::SE2& b_in_a,
                               double max_range_m, double tolerance_m);

class LoopClosingMapper {
 public:
  explicit LoopClosingMapper(LoopClosingConfig config = {});
  /// One scan (points in the robot frame) with the local estimator's pose, and optionally a
  /// second estimate of the same motion in its own frame (the front end's pose), which stands in
  /// for the local estimator on a chain edge where the two disagree (chain_gate_chi2).
  /// `step_covariance` (optional): the covariance of the motion since the previous scan (x, y in
  /// any frame, yaw), as the estimator that made it knows it; it widens the wide search's window
  /// where it is larger than chain_noise's (LoopClosingConfig::chain_noise).
  void add(const std::vector<Eigen::Vector2d>& points_robot, const math::SE2& local_pose,
           const math::SE2* reference_pose = nullptr,
           const Eigen::Matrix3d* step_covariance = nullptr);
  /// The final pose of every scan added, in order.
  std::vector<math::SE2> trajectory() const;
  /// The last scan's final pose (trajectory().back()); the origin before the first scan.
  math::SE2 lastPose() const;
  int loopClosures() const { return graph_.numLoopEdges(); }
  int nodes() const { return graph_.numNodes(); }
  long attempts() const { return attempts_; }
  /// Matches above min_loop_score that the free-space check rejected.
  long freeSpaceRejections() const { return free_space_rejected_; }
  /// Each loop edge as found: the scans (indices in the order added) of its two nodes, the
  /// measured relative pose of the newer in the older's frame, the fine match's score, and
  /// whether the wide search found it.
  struct LoopEdge {
    int scan_from, scan_to;
    math::SE2 relative;
    double score;
    bool wide = false;
  };
  const std::vector<LoopEdge>& loopEdges() const { return loop_edges_; }
  /// Chain edges that took the reference's relative pose (the local estimator failed the gate).
  int chainEdgesReplaced() const { return chain_replaced_; }
  /// The wide search: attempts, matches that passed the local checks, and pairs of them that
  /// agreed (each pair adds two loop edges, counted in loopClosures()).
  long wideAttempts() const { return wide_attempts_; }
  long wideMatches() const { return wide_matches_; }
  long wideConfirmed() const { return wide_confirmed_; }
  /// Wide matches dropped as ambiguous in rotation (wide_ambiguity_ratio), and wide searches the
  /// budget cut short (wide_max_bounds; such a search's match counts as ambiguous).
  long wideAmbiguous() const { return wide_ambiguous_; }
  long wideBudgetCut() const { return wide_budget_cut_; }
  /// Wide matches dropped because they lie beyond the window of the node they join (see
  /// LoopClosingConfig::wide_search).
  long wideBeyondWindow() const { return wide_beyond_window_; }
  /// Wall-clock seconds spent in the wide search (its cost, for the tools' summaries).
  double wideSeconds() const { return wide_seconds_; }

 private:
  bool tryLoop(int node);
  /// The accumulated stds (heading, position) of node n's pose relative to node k < n: sigma_yaw^2
  /// = sum v_i, sigma_xy^2 = sum t_i + sum v_i |p_n - p_i|^2 over the nodes i in (k, n].
  std::pair<double, double> accumulatedStd(int k, int n) const;
  /// The wide search of node n (see LoopClosingConfig::wide_search); true when it closed a loop.
  bool tryWide(int n);
  /// The candidate k for node n with n's pose in k's frame `prior`: the coarse (unless
  /// coarse_search is false: the prior is already a coarse match) and fine matches against the
  /// scans of the `submap` nodes (k's frame), the score and free-space checks; the measured pose
  /// of n in k's frame.
  struct Verified {
    math::SE2 n_in_k;
    Eigen::Matrix3d information;
    double score;
  };
  std::optional<Verified> verify(int n, int k, const math::SE2& prior,
                                 const std::vector<int>& submap, double max_free_space_violations,
                                 bool coarse_search);
  /// The free-space check of node n matched at n_in_k in the frame of node k (xk_inv: k's pose
  /// inverted) against the submap nodes: the share of points seen through (see
  /// freeSpaceViolationShare).
  double freeSpaceShare(int n, const math::SE2& xk_inv, const math::SE2& n_in_k,
                        const std::vector<int>& submap) const;

  LoopClosingConfig config_;
  PoseGraph2D graph_;
  struct NodeData {
    math::SE2 local;      // the local estimator's pose at the node
    int scan = 0;         // the scan the node was made from (index in the order added)
    math::SE2 reference;  // the reference pose at the node (when given)
    bool has_reference = false;
    std::vector<Eigen::Vector2d> points;
    double path_m = 0.0;  // the chain's length from the first node
    // Prefix sums over the nodes up to this one of the variance each added since the node
    // before (v_i heading, t_i position) and of v_i's lever-arm moments at the local position
    // p_i: yaw_var = sum v_i, yaw_var_p = sum v_i p_i, yaw_var_pp = sum v_i |p_i|^2, xy_var =
    // sum t_i. See accumulatedStd.
    double yaw_var = 0.0, yaw_var_pp = 0.0, xy_var = 0.0;
    Eigen::Vector2d yaw_var_p = Eigen::Vector2d::Zero();
  };
  std::vector<NodeData> nodes_;
  struct WideHypothesis {
    int n, k;
    Verified match;
    math::SE2 correction;  // the graph pose of n it implies, times n's graph pose inverted
  };
  std::optional<WideHypothesis> wide_pending_;
  int last_wide_node_ = -1000000;
  long wide_attempts_ = 0, wide_matches_ = 0, wide_confirmed_ = 0, wide_ambiguous_ = 0;
  long wide_budget_cut_ = 0, wide_beyond_window_ = 0;
  double wide_seconds_ = 0.0;
  struct ScanRef {
    int node;
    math::SE2 offset;  // local motion since the node
  };
  std::vector<ScanRef> scans_;
  // The variance added since the last node (heading, position), and the last scan's local pose.
  double pending_yaw_var_ = 0.0, pending_xy_var_ = 0.0;
  math::SE2 last_local_;
  long attempts_ = 0;
  int chain_replaced_ = 0;
  long free_space_rejected_ = 0;
  std::vector<LoopEdge> loop_edges_;
};

}  // namespace adaptive_perception::slam
