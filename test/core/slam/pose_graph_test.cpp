// The pose graph against cases with known optima (a consistent chain stays put, a loop edge
// spreads a closing error along the chain as the least-squares solution does, a wrong loop edge is
// held off by the robust loss, a wrong chain edge is undone by confirmed loops across it under the
// chain's Huber loss, which spreads a correction as least squares does), and the loop-closing
// mapper closing a drifting square in a synthetic room, by its local search and, beyond that
// search's window, by the wide search.
#include "adaptive_perception/slam/pose_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include "synthetic_room.h"

namespace slam = adaptive_perception::slam;
namespace math = adaptive_perception::math;

namespace {

Eigen::Matrix3d info(double sd_m, double sd_rad) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  m(0, 0) = m(1, 1) = 1.0 / (sd_m * sd_m);
  m(2, 2) = 1.0 / (sd_rad * sd_rad);
  return m;
}

TEST(PoseGraph2D, ConsistentChainIsItsOwnOptimum) {
  slam::PoseGraph2D g;
  math::SE2 x;
  g.addNode(x);
  const math::SE2 step(1.0, 0.0, M_PI / 2);
  for (int i = 1; i <= 4; ++i) {
    x = x * step;
    g.addNode(x);
    g.addEdge(i - 1, i, step, info(0.1, 0.05));
  }
  g.addEdge(4, 0, math::SE2(), info(0.1, 0.05), true);  // the square closes exactly
  EXPECT_NEAR(g.optimize(), 0.0, 1e-12);
  EXPECT_NEAR(g.node(2).x_m, 1.0, 1e-9);
  EXPECT_NEAR(g.node(2).y_m, 1.0, 1e-9);
  EXPECT_EQ(g.numLoopEdges(), 1);
}

/// Nodes 0..4 at 1 m steps along x, four edges measuring those steps, and an edge saying node 4
/// is 3.6 m from node 0 (a loop edge, under the robust loss, or an ordinary one), all weighted
/// alike.
slam::PoseGraph2D fourStepsAndALoopOf3_6m(bool robust_loop) {
  slam::PoseGraph2D g;
  for (int i = 0; i <= 4; ++i) g.addNode(math::SE2(i * 1.0, 0.0, 0.0));
  for (int i = 1; i <= 4; ++i) g.addEdge(i - 1, i, math::SE2(1.0, 0.0, 0.0), info(0.1, 0.01));
  g.addEdge(0, 4, math::SE2(3.6, 0.0, 0.0), info(0.1, 0.01), robust_loop);
  return g;
}

TEST(PoseGraph2D, LoopEdgeSpreadsTheErrorLikeLeastSquares) {
  // Four translations of 1 m along x measured with equal weight, a loop edge saying node 4 is 3.6 m
  // from node 0 (pure translations, no rotation). Were the loop an ordinary edge, least squares
  // would make each step 1 - 0.4 / 5 = 0.92 m (the next test); the Cauchy loss on the loop edge
  // (its whitened residual is about 3) makes it pull less, so the span lies in (3.68, 4) and
  // the steps stay equal.
  slam::PoseGraph2D g = fourStepsAndALoopOf3_6m(true);
  g.optimize();
  const double span = g.node(4).x_m - g.node(0).x_m;
  EXPECT_GT(span, 3.68 - 1e-6);
  EXPECT_LT(span, 4.0);
  for (int i = 1; i <= 4; ++i)  // equal steps: the error is spread evenly
    EXPECT_NEAR(g.node(i).x_m - g.node(i - 1).x_m, span / 4, 1e-4);
  EXPECT_NEAR(g.node(0).x_m, 0.0, 1e-12);  // node 0 held fixed
}

TEST(PoseGraph2D, LinearCaseWithoutRobustLossMatchesTheClosedForm) {
  // The same graph with the loop as an ordinary edge: weighted least squares over five equal
  // residuals -> each step 0.92 m, the span 3.68 m.
  slam::PoseGraph2D g = fourStepsAndALoopOf3_6m(false);
  g.optimize();
  EXPECT_NEAR(g.node(4).x_m, 3.68, 1e-6);
  EXPECT_NEAR(g.node(1).x_m, 0.92, 1e-6);
}

TEST(PoseGraph2D, AWrongLoopEdgeIsHeldOff) {
  // A chain of 10 steps with tight edges and one loop edge that is 5 m wrong: the robust loss
  // keeps the chain within a few centimetres of its measured shape.
  slam::PoseGraph2D g;
  for (int i = 0; i <= 10; ++i) g.addNode(math::SE2(i * 1.0, 0.0, 0.0));
  for (int i = 1; i <= 10; ++i) g.addEdge(i - 1, i, math::SE2(1.0, 0.0, 0.0), info(0.02, 0.01));
  g.addEdge(0, 10, math::SE2(5.0, 0.0, 0.0), info(0.05, 0.02), true);
  g.optimize();
  EXPECT_NEAR(g.node(10).x_m, 10.0, 0.1);
}

// Two laps of a 10 x 10 m square, 1 m a node, chain edges measuring the true steps except one in
// the second lap that says 3.6 m more along x (the local estimator jumped and the gate let it
// through); a loop edge from every second-lap node to its first-lap twin, under its Cauchy loss
// (loops_robust) or not. Returns the largest position error after the optimisation.
double plantedJumpError(bool robust_chain, bool loops_robust) {
  const double huber_scale = slam::LoopClosingConfig().chain_huber_scale;
  std::vector<math::SE2> truth;
  for (int lap = 0; lap < 2; ++lap)
    for (int side = 0; side < 4; ++side)
      for (int k = 0; k < 10; ++k) {
        const double a = side * M_PI / 2;
        const Eigen::Vector2d corner[4] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
        truth.emplace_back(corner[side].x() + k * std::cos(a), corner[side].y() + k * std::sin(a),
                           a);
      }
  const int n = static_cast<int>(truth.size()), jump = 55;  // a second-lap edge
  slam::PoseGraph2D g;
  math::SE2 x = truth.front();
  g.addNode(x);
  for (int i = 1; i < n; ++i) {
    math::SE2 z = math::between(truth[i - 1], truth[i]);
    if (i == jump) z = z * math::SE2(3.6, 0.0, 0.0);
    x = x * z;
    g.addNode(x);
    if (robust_chain)
      g.addRobustChainEdge(i - 1, i, z, info(0.02, 0.01), huber_scale);
    else
      g.addEdge(i - 1, i, z, info(0.02, 0.01));
  }
  for (int i = n / 2; i < n; ++i)
    g.addEdge(i - n / 2, i, math::SE2(), info(0.05, 0.02), true, loops_robust);
  g.optimize(100);
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
    worst = std::max(worst, std::hypot(g.node(i).x_m - truth[i].x_m, g.node(i).y_m - truth[i].y_m));
  return worst;
}

TEST(PoseGraph2D, AWrongChainEdgeIsUndoneByTheLoopsAcrossIt) {
  // The loops enter as confirmed ones do (without their Cauchy loss). Least squares spreads the
  // planted 3.6 m over both laps (2.36 m off at worst); the Huber loss on the chain (Huber's
  // 1.345) lets the loops on both sides of the wrong edge hold it: what is left is the edge's
  // bounded pull, 1.345 of its standard deviations' worth, spread over the loops.
  const double plain = plantedJumpError(false, false), robust = plantedJumpError(true, false);
  const double cauchy_loops = plantedJumpError(true, true);
  std::printf(
      "planted 3.6 m chain jump: worst position error %.3f m (quadratic chain), %.3f m "
      "(Huber chain); with every loop under its Cauchy loss %.3f m (each loop is discounted "
      "alone)\n",
      plain, robust, cauchy_loops);
  EXPECT_GT(plain, 2.0);
  EXPECT_LT(robust, 0.2);
}

TEST(PoseGraph2D, AHuberChainSpreadsALoopCorrectionAsLeastSquaresDoes) {
  // The case of LinearCaseWithoutRobustLoss with the loop as an ordinary edge and Huber chain
  // edges of a threshold above the residuals (each step's whitened residual is 0.8): the same
  // closed form, 0.92 m a step. Huber is quadratic there, so the correction is not concentrated.
  slam::PoseGraph2D g;
  for (int i = 0; i <= 4; ++i) g.addNode(math::SE2(i * 1.0, 0.0, 0.0));
  for (int i = 1; i <= 4; ++i)
    g.addRobustChainEdge(i - 1, i, math::SE2(1.0, 0.0, 0.0), info(0.1, 0.01), 3.0);
  g.addEdge(0, 4, math::SE2(3.6, 0.0, 0.0), info(0.1, 0.01), false);
  g.optimize();
  EXPECT_NEAR(g.node(4).x_m, 3.68, 1e-6);
  for (int i = 1; i <= 4; ++i) EXPECT_NEAR(g.node(i).x_m - g.node(i - 1).x_m, 0.92, 1e-6);
  EXPECT_THROW(g.addRobustChainEdge(0, 1, math::SE2(), info(0.1, 0.01), 0.0),
               std::invalid_argument);
}

// Laps of a 7.6 x 2.6 m rectangle in the synthetic room, 0.1 m a pose, facing along each side.
std::vector<math::SE2> rectangleLaps(int laps) {
  const std::vector<Eigen::Vector2d> corners = {{1.2, 1.0}, {8.8, 1.0}, {8.8, 3.6}, {1.2, 3.6}};
  std::vector<math::SE2> out;
  for (int lap = 0; lap < laps; ++lap)
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector2d a = corners[c], b = corners[(c + 1) % 4];
      const double yaw = std::atan2(b.y() - a.y(), b.x() - a.x());
      const int n = static_cast<int>(std::round((b - a).norm() / 0.1));
      for (int k = 0; k < n; ++k)
        out.emplace_back(a.x() + (b - a).x() * k / n, a.y() + (b - a).y() * k / n, yaw);
    }
  return out;
}

// Feeds `mapper` a scan from every pose of `truth` with a local estimator that turns
// turn_bias_deg_per_m too much per metre driven; returns the estimator's poses.
std::vector<math::SE2> driveWithTurnBias(const std::vector<math::SE2>& truth,
                                         double turn_bias_deg_per_m, unsigned seed,
                                         slam::LoopClosingMapper* mapper) {
  std::mt19937 rng(seed);
  math::SE2 local = truth.front();
  std::vector<math::SE2> locals{local};
  mapper->add(adaptive_perception::test::scanFrom(truth.front(), &rng, 0.01), local);
  for (size_t i = 1; i < truth.size(); ++i) {
    const math::SE2 d = math::between(truth[i - 1], truth[i]);
    const double turn_bias = turn_bias_deg_per_m * M_PI / 180.0 * std::hypot(d.x_m, d.y_m);
    local = local * math::SE2(d.x_m, d.y_m, d.yaw_rad + turn_bias);
    locals.push_back(local);
    mapper->add(adaptive_perception::test::scanFrom(truth[i], &rng, 0.01), local);
  }
  return locals;
}

// The robot drives a rectangle in the synthetic room twice, at 0.1 m a scan; the local poses it
// is given turn 0.3 degrees too much per metre, so the second lap lies up to about a metre off
// the first. The mapper closes the loop at the first lap's nodes and pulls the second lap back.
TEST(LoopClosingMapper, ClosesADriftingLoopInASyntheticRoom) {
  std::vector<math::SE2> truth = rectangleLaps(2);
  truth.push_back(truth.front());
  slam::LoopClosingMapper mapper;
  const std::vector<math::SE2> locals = driveWithTurnBias(truth, 0.3, 3, &mapper);
  const std::vector<math::SE2> out = mapper.trajectory();
  ASSERT_EQ(out.size(), truth.size());
  double worst_in = 0.0, worst_out = 0.0;
  for (size_t i = truth.size() / 2; i < truth.size(); ++i) {  // the second lap
    worst_in =
        std::max(worst_in, std::hypot(locals[i].x_m - truth[i].x_m, locals[i].y_m - truth[i].y_m));
    worst_out =
        std::max(worst_out, std::hypot(out[i].x_m - truth[i].x_m, out[i].y_m - truth[i].y_m));
  }
  std::printf("loop closing: %d loop edges, %ld attempts; second lap worst error %.3f -> %.3f m\n",
              mapper.loopClosures(), mapper.attempts(), worst_in, worst_out);
  EXPECT_GT(worst_in, 0.5);
  EXPECT_GE(mapper.loopClosures(), 1);
  EXPECT_LT(worst_out, 0.25 * worst_in);
}

// The same room driven round three times with a local estimator that turns 0.5 degrees too much
// per metre: when the first lap ends (20.4 m) it is 10 degrees and 2 m off, beyond the local
// window (coarse_search_xy_m). Its noise is the generic wheel-odometry model's
// (LoopClosingConfig::chain_noise's default: 0.2 rad a metre), so the window after a lap is about
// a radian and 9 m. The local search is switched off (in this small room it would close
// the loop bit by bit before the drift grew), so only the wide search can close it: each loop
// edge it adds holds the true relative pose (within what the drift bends the stretch of chain it
// is matched against: 0.5 degrees a metre over +-max_range_m), they come in agreeing pairs, and
// the last lap is pulled most of the way back; without it the laps stay where the estimator put
// them.
TEST(LoopClosingMapper, TheWideSearchClosesALoopBeyondTheLocalWindow) {
  std::vector<math::SE2> truth = rectangleLaps(3);
  auto run = [&](bool wide, slam::LoopClosingMapper* out_mapper) {
    slam::LoopClosingConfig c;
    c.max_candidates_per_node = 0;  // no local loop closing
    c.wide_search = wide;
    c.wide_min_loop_m = 15.0;  // the room's laps are 20.4 m
    c.max_range_m = 12.0;
    slam::LoopClosingMapper mapper(c);
    const std::vector<math::SE2> locals = driveWithTurnBias(truth, 0.5, 8, &mapper);
    const std::vector<math::SE2> traj = mapper.trajectory();
    // The last lap's worst position error, after aligning the first pose (node 0 is fixed at the
    // estimator's first pose, which is the truth's).
    double worst = 0.0, worst_local = 0.0;
    for (size_t i = 2 * truth.size() / 3; i < truth.size(); ++i) {
      worst = std::max(worst, std::hypot(traj[i].x_m - truth[i].x_m, traj[i].y_m - truth[i].y_m));
      worst_local = std::max(
          worst_local, std::hypot(locals[i].x_m - truth[i].x_m, locals[i].y_m - truth[i].y_m));
    }
    if (out_mapper) *out_mapper = mapper;
    return std::make_pair(worst, worst_local);
  };
  slam::LoopClosingMapper with_mapper, without_mapper;
  const auto [with_wide, local_err] = run(true, &with_mapper);
  const auto [without_wide, local_err2] = run(false, &without_mapper);
  std::printf(
      "wide search: last lap worst error %.3f m (local estimator %.3f m, without the wide "
      "search %.3f m); %ld attempts, %ld matches, %ld confirmed, %d loop edges\n",
      with_wide, local_err, without_wide, with_mapper.wideAttempts(), with_mapper.wideMatches(),
      with_mapper.wideConfirmed(), with_mapper.loopClosures());
  EXPECT_GT(local_err, 1.5);  // beyond the local window
  EXPECT_GE(with_mapper.wideConfirmed(), 1);
  EXPECT_EQ(with_mapper.loopClosures(), 2 * with_mapper.wideConfirmed());
  for (const auto& e : with_mapper.loopEdges()) {
    const math::SE2 t = math::between(truth[e.scan_from], truth[e.scan_to]);
    std::printf("wide loop edge %d -> %d: off by %.3f m, %.4f rad\n", e.scan_from, e.scan_to,
                std::hypot(e.relative.x_m - t.x_m, e.relative.y_m - t.y_m),
                math::angleDiff(e.relative.yaw_rad, t.yaw_rad));
    EXPECT_LT(std::hypot(e.relative.x_m - t.x_m, e.relative.y_m - t.y_m), 0.05) << e.scan_to;
    EXPECT_LT(std::fabs(math::angleDiff(e.relative.yaw_rad, t.yaw_rad)), 0.03) << e.scan_to;
  }
  // Between the loop edges the chain still turns 0.5 degrees a metre: not exact.
  EXPECT_LT(with_wide, 0.25 * without_wide);
  EXPECT_EQ(without_mapper.loopClosures(), 0);
  EXPECT_GT(without_wide, 1.5);
}

// The room driven round three times by an estimator that is exact but for one slip: over ten
// scans at the first lap's third corner it turns 0.12 rad a scan too much (1.2 rad in all, as a
// front end that keeps the wheel odometry's heading in a round hall may), and says so: those
// steps come with a heading std of 0.15 rad (the step covariance a front end reports along a
// direction its scan match cannot see). The rest of the run is turned by 1.2 rad, twice the
// wide search's former fixed cap (0.6 rad). With the step covariances the window grows to what
// the chain may have turned (0.5 + 3 sqrt(10) 0.15 = 1.92 rad), the loop is closed by agreeing
// pairs whose edges hold the true relative pose, and the last lap comes back. The room's right
// angles make an alias nearer the estimate than the truth (turned 1.57 - 1.2 rad): in the wide
// window it scores nearly as well as the truth and is dropped as ambiguous
// (wide_ambiguity_ratio); without the step covariances the window is the estimator's own noise
// model's (its corners' turns: about 0.75 rad), holds the alias but not the truth, and the laps
// stay turned (two alias matches even agree).
TEST(LoopClosingMapper, TheWideSearchTurnsAsFarAsTheChainIsUncertain) {
  const std::vector<math::SE2> truth = rectangleLaps(3);
  const size_t slip_from = 100, slip_scans = 10;  // the third corner is at scan 102
  const double slip_rad = 0.12;
  auto run = [&](bool report_uncertainty, slam::LoopClosingMapper* out_mapper) {
    slam::LoopClosingConfig c;
    c.max_candidates_per_node = 0;  // the wide search alone
    c.wide_min_loop_m = 15.0;
    c.max_range_m = 12.0;
    c.wide_drift_per_m = 0.0;  // exact but for the slip: no drift with the chain's length
    // The front end's noise model (LaserSlamConfig::front_end_motion).
    c.chain_noise = adaptive_perception::localization::MotionModelConfig{0.025,  0.0125,  0.02,
                                                                         0.0025, 0.00025, 0.00025};
    slam::LoopClosingMapper mapper(c);
    std::mt19937 rng(5);
    math::SE2 local = truth.front();
    Eigen::Matrix3d slip_cov = Eigen::Matrix3d::Zero();
    slip_cov(2, 2) = 0.15 * 0.15;
    for (size_t i = 0; i < truth.size(); ++i) {
      bool slipping = false;
      if (i > 0) {
        const math::SE2 d = math::between(truth[i - 1], truth[i]);
        slipping = i >= slip_from && i < slip_from + slip_scans;
        local = local * math::SE2(d.x_m, d.y_m, d.yaw_rad + (slipping ? slip_rad : 0.0));
      }
      mapper.add(adaptive_perception::test::scanFrom(truth[i], &rng, 0.01), local, nullptr,
                 slipping && report_uncertainty ? &slip_cov : nullptr);
    }
    const std::vector<math::SE2> traj = mapper.trajectory();
    double worst = 0.0;
    for (size_t i = 2 * truth.size() / 3; i < truth.size(); ++i)
      worst = std::max(worst, std::hypot(traj[i].x_m - truth[i].x_m, traj[i].y_m - truth[i].y_m));
    *out_mapper = mapper;
    return worst;
  };
  slam::LoopClosingMapper with_mapper, without_mapper;
  const double with_cov = run(true, &with_mapper), without_cov = run(false, &without_mapper);
  std::printf(
      "a 1.2 rad slip: last lap worst error %.3f m with the step covariances (%ld attempts, %ld "
      "matches, %ld confirmed), %.3f m without (%ld confirmed)\n",
      with_cov, with_mapper.wideAttempts(), with_mapper.wideMatches(), with_mapper.wideConfirmed(),
      without_cov, without_mapper.wideConfirmed());
  EXPECT_GE(with_mapper.wideConfirmed(), 1);
  for (const auto& e : with_mapper.loopEdges()) {
    const math::SE2 t = math::between(truth[e.scan_from], truth[e.scan_to]);
    EXPECT_LT(std::hypot(e.relative.x_m - t.x_m, e.relative.y_m - t.y_m), 0.05) << e.scan_to;
    EXPECT_LT(std::fabs(math::angleDiff(e.relative.yaw_rad, t.yaw_rad)), 0.03) << e.scan_to;
  }
  EXPECT_GT(without_cov, 3.0);  // the slip turned the laps by 1.2 rad
  EXPECT_LT(with_cov, 0.3);
}

// One lap of the rectangle; the local estimator (the EKF) is exact but for one jump of 0.2 rad
// halfway along the second side (a wrong line pairing), which it keeps from then on. The front
// end's poses are exact. The chain edge across the jump fails the gate and takes the front end's
// relative pose, so the lap after the jump stays where it is; without the reference the jump
// turns the rest of the lap.
TEST(LoopClosingMapper, AChainEdgeWhereTheLocalEstimatorJumpsTakesTheFrontEnd) {
  const std::vector<math::SE2> truth = rectangleLaps(1);
  const size_t jump_at = 90;
  auto run = [&](bool with_reference, int* replaced) {
    slam::LoopClosingConfig c;
    c.max_candidates_per_node = 0;  // the chain alone: no loop edge may hide the effect
    slam::LoopClosingMapper mapper(c);
    std::mt19937 rng(4);
    const math::SE2 jump(0.0, 0.0, 0.2);
    for (size_t i = 0; i < truth.size(); ++i) {
      // The jumped estimator: the truth turned by 0.2 rad about the pose where it jumped.
      const math::SE2 local =
          i < jump_at ? truth[i] : truth[jump_at] * jump * math::between(truth[jump_at], truth[i]);
      mapper.add(adaptive_perception::test::scanFrom(truth[i], &rng, 0.01), local,
                 with_reference ? &truth[i] : nullptr);
    }
    *replaced = mapper.chainEdgesReplaced();
    double worst = 0.0;
    const std::vector<math::SE2> out = mapper.trajectory();
    for (size_t i = jump_at + 10; i < truth.size(); ++i)
      worst = std::max(worst, std::fabs(math::angleDiff(out[i].yaw_rad, truth[i].yaw_rad)));
    return worst;
  };
  int replaced_with = 0, replaced_without = 0;
  const double with_ref = run(true, &replaced_with), without_ref = run(false, &replaced_without);
  std::printf(
      "a 0.2 rad jump of the local estimator: worst yaw after it %.4f rad with the front "
      "end's reference (%d chain edge(s) replaced), %.4f without\n",
      with_ref, replaced_with, without_ref);
  EXPECT_EQ(replaced_with, 1);
  EXPECT_EQ(replaced_without, 0);
  EXPECT_NEAR(without_ref, 0.2, 0.01);
  EXPECT_LT(with_ref, 0.01);
}

// Two scans of a 4 x 4 m room from its centre facing east; in the second the room is 1 m further
// east (the robot stood 1 m west). Matched as if taken from the same pose, the second scan's points
// all lie on or behind the first's walls, but the first scan's east wall (x = 2) stands in front
// of the second's returns, which reach x = 3 (or the side walls): a beam at bearing t hits the
// first's wall at 2 / cos t and the second's at min(3 / cos t, 2 / |sin t|). The share counted
// from that geometry, beam by beam, is the reference; at the true offset the share is 0.
TEST(FreeSpaceViolationShare, AWrongAlignmentPutsWallsInTheOtherScansFreeSpace) {
  using adaptive_perception::test::Segment;
  const std::vector<Segment> room{
      {{-2, -2}, {2, -2}}, {{2, -2}, {2, 2}}, {{2, 2}, {-2, 2}}, {{-2, 2}, {-2, -2}}};
  const math::SE2 a_pose(0.0, 0.0, 0.0), b_pose(-1.0, 0.0, 0.0);
  const std::vector<Eigen::Vector2d> a =
      adaptive_perception::test::scanOf(room, a_pose, nullptr, 0.0, 20.0);
  const std::vector<Eigen::Vector2d> b =
      adaptive_perception::test::scanOf(room, b_pose, nullptr, 0.0, 20.0);
  ASSERT_EQ(a.size(), 181u);
  const double tolerance_m = 0.3;
  int expected = 0;
  for (int i = 0; i <= 180; ++i) {
    const double t = (i - 90) * M_PI / 180.0;
    const double d = std::min(2.0 / std::cos(t), 2.0 / std::max(std::fabs(std::sin(t)), 1e-9));
    const double r = std::min(3.0 / std::cos(t), 2.0 / std::max(std::fabs(std::sin(t)), 1e-9));
    expected += d < r - tolerance_m - 0.05 * r;
  }
  const double wrong = slam::freeSpaceViolationShare(a, b, math::SE2(), 25.0, tolerance_m);
  const double right =
      slam::freeSpaceViolationShare(a, b, math::between(a_pose, b_pose), 25.0, tolerance_m);
  std::printf(
      "free-space violations: %.3f at a 1 m wrong alignment (geometry: %d of 181), %.3f at "
      "the right one\n",
      wrong, expected, right);
  EXPECT_GT(expected, 60);
  EXPECT_NEAR(wrong, expected / 181.0, 2.0 / 181.0);  // a beam either side of a 1-degree bin edge
  EXPECT_EQ(right, 0.0);
}

TEST(PoseGraph2D, RefusesBadEdges) {
  slam::PoseGraph2D g;
  g.addNode({});
  g.addNode({});
  EXPECT_THROW(g.addEdge(0, 2, {}, info(0.1, 0.1)), std::invalid_argument);
  EXPECT_THROW(g.addEdge(0, 1, {}, Eigen::Matrix3d::Zero()), std::invalid_argument);
  slam::LoopClosingConfig c;
  c.min_loop_score = 2.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = slam::LoopClosingConfig();
  c.chain_gate_chi2 = 0.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = slam::LoopClosingConfig();
  c.max_free_space_violations = 1.5;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
