// The likelihood field against its closed form, the correlative matcher recovering a known pose
// offset in a synthetic room, and laser odometry removing a wheel-odometry bias along a simulated
// drive and bridging an odometry that stalls and then jumps.
#include "adaptive_perception/slam/scan_matcher.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "adaptive_perception/math/angles.h"
#include "synthetic_room.h"

namespace slam = adaptive_perception::slam;
namespace math = adaptive_perception::math;
using adaptive_perception::test::roomPoints;
using adaptive_perception::test::scanFrom;

namespace {

TEST(LikelihoodField, MatchesTheGaussianOfTheDistance) {
  // One map point at the origin: the field at distance d is exp(-d^2 / (2 s^2)).
  const slam::LikelihoodField f({Eigen::Vector2d(0, 0)}, 0.05, 0.1, 1.0);
  EXPECT_NEAR(f.at({0, 0}), 1.0, 1e-6);
  for (double d : {0.05, 0.1, 0.2, 0.3})
    EXPECT_NEAR(f.at({d, 0}), std::exp(-d * d / (2 * 0.01)), 1e-5) << d;
  // Between cells: bilinear, so between its neighbours' values.
  const double mid = f.at({0.075, 0});
  EXPECT_LT(mid, f.at({0.05, 0}));
  EXPECT_GT(mid, f.at({0.1, 0}));
  EXPECT_EQ(f.at({5.0, 0}), 0.0);  // outside
  EXPECT_THROW(slam::LikelihoodField({}, 0.05, 0.1, 1.0), std::invalid_argument);
}

TEST(LikelihoodField, EqualsTheBruteForceFieldOfTheNearestMapCell) {
  // Random map points; the reference: every cell's distance to the nearest map point's cell, by
  // brute force, through the Gaussian. Equal within 4 hit_std, below exp(-8) beyond.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < 60; ++i) pts.push_back({u(rng), 0.5 * u(rng)});
  const double res = 0.05, sd = 0.1;
  const slam::LikelihoodField f(pts, res, sd, 0.6);
  const cv::Mat& v = f.values();
  std::vector<Eigen::Vector2i> cells;
  for (const auto& p : pts)
    cells.emplace_back(static_cast<int>(std::lround((p.x() - f.origin().x()) / res)),
                       static_cast<int>(std::lround((p.y() - f.origin().y()) / res)));
  int near = 0;
  for (int y = 0; y < v.rows; ++y)
    for (int x = 0; x < v.cols; ++x) {
      double d2 = 1e300;
      for (const auto& c : cells)
        d2 = std::min(d2, res * res * ((x - c.x()) * (x - c.x()) + (y - c.y()) * (y - c.y())));
      const double expected = std::exp(-d2 / (2 * sd * sd));
      if (d2 <= 16 * sd * sd) {
        ASSERT_NEAR(v.at<float>(y, x), expected, 1e-6) << x << "," << y;
        ++near;
      } else {
        ASSERT_LE(v.at<float>(y, x), std::exp(-8.0) + 1e-6) << x << "," << y;
      }
    }
  EXPECT_GT(near, 1000);
}

TEST(ScanMatcher, GeometricInformationOfAWallIsTheClosedForm) {
  // A straight wall y = 2 m sampled every 5 cm from x = -1 to 1, seen from the origin, its own
  // field: every return lies on its map point (weight 1) and its normal is (0, 1). The row of a
  // return at (x, 2) is [0, 1, x] (d(Rp)/dyaw = (-2, x)), so H = sum [0 0 0; 0 1 x; 0 x x^2] /
  // hit_std^2: nothing along the wall.
  std::vector<Eigen::Vector2d> wall;
  double n = 0.0, sx = 0.0, sxx = 0.0;
  for (int k = -20; k <= 20; ++k) {
    const double x = 0.05 * k + 0.013;  // off-centre, so that the cross term is not 0
    wall.emplace_back(x, 2.0);
    n += 1.0;
    sx += x;
    sxx += x * x;
  }
  const double sd = 0.1;
  const slam::LikelihoodField field(wall, 0.01, sd, 0.5, 0.3);
  const Eigen::Matrix3d H =
      slam::geometricMatchInformation(field, wall, math::SE2(), sd, 0.3);
  const double s2 = sd * sd;
  EXPECT_NEAR(H(0, 0), 0.0, 1e-6 * n / s2);
  EXPECT_NEAR(H(0, 1), 0.0, 1e-6 * n / s2);
  EXPECT_NEAR(H(1, 1), n / s2, 0.01 * n / s2);
  EXPECT_NEAR(H(1, 2), sx / s2, 0.01 * n / s2);
  EXPECT_NEAR(H(2, 2), sxx / s2, 0.01 * sxx / s2);

  // A circular wall of radius 4 m about the origin seen from (1, 0) facing +y: every normal is
  // radial, so a turn about the centre, which moves the robot by (0, 1) per radian and turns it
  // by 1, is not seen: v^T H v is about 0 against H's largest eigenvalue.
  const math::SE2 pose(1.0, 0.0, M_PI / 2);
  std::vector<Eigen::Vector2d> circle_map, circle_robot;
  for (int k = 0; k < 720; ++k) {
    const double a = 2 * M_PI * k / 720;
    circle_map.emplace_back(4.0 * std::cos(a), 4.0 * std::sin(a));
  }
  for (const auto& q : circle_map) circle_robot.push_back(pose.inverse().transformPoint(q));
  const slam::LikelihoodField round(circle_map, 0.02, sd, 0.5, 0.3);
  const Eigen::Matrix3d Hc = slam::geometricMatchInformation(round, circle_robot, pose, sd, 0.3);
  const Eigen::Vector3d v(0.0, 1.0, 1.0);
  const double largest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(Hc).eigenvalues()(2);
  EXPECT_LT(v.dot(Hc * v) / v.squaredNorm(), 1e-4 * largest);
  EXPECT_GT(Hc(0, 0), 0.1 * largest);  // the translations are seen
  EXPECT_GT(Hc(1, 1), 0.1 * largest);
}

TEST(ScanMatcher, GeometricInformationOfADenseNoisyCorridorHasNothingAlongIt) {
  // A bare corridor 2 m wide seen by lasers of 181 to 3601 beams over 180 degrees with 1 to 3 cm
  // of range noise, 8 m reach. Near a wall a dense laser's beams are mm apart: a neighbourhood of
  // a fixed count of returns spanned a few cm there, and the noise made many of them "corners"
  // that claimed the corridor's length (the simulated loop bag's 361-beam laser shrank its first
  // corridor by 0.46 m in 15 m). Taken over wall_gap_m, the walls stay walls: along the corridor
  // the information stays far below min_match_information times an odometry step's (0.1 m:
  // odom_std_m + odom_std_per_m * 0.1 = 0.03 m).
  const std::vector<adaptive_perception::test::Segment> walls{{{0, 0}, {100, 0}},
                                                              {{0, 2}, {100, 2}}};
  const slam::LaserOdometryConfig lo;
  const double step_sd = lo.odom_std_m + lo.odom_std_per_m * 0.1;
  const double sd = lo.matcher.hit_std_m;
  const math::SE2 pose(10.0, 1.0, 0.0);
  for (int beams : {181, 361, 1441, 3601})
    for (double noise_m : {0.01, 0.015, 0.03}) {
      std::mt19937 rng(5);
      const auto scan = adaptive_perception::test::scanOf(walls, pose, &rng, noise_m, 8.0, beams);
      std::vector<Eigen::Vector2d> map;
      for (const auto& p : scan) map.push_back(pose.transformPoint(p));
      const slam::LikelihoodField field(map, 0.05, sd, 1.0, lo.connect_gap_m);
      const Eigen::Matrix3d H =
          slam::geometricMatchInformation(field, scan, pose, sd, lo.connect_gap_m);
      const double lambda_along = H(0, 0) * step_sd * step_sd;
      std::printf("corridor, %d beams, %.3f m noise: information along it %.1f, across %.1f "
                  "(1/m^2); along, in odometry steps' %.3f\n",
                  beams, noise_m, H(0, 0), H(1, 1), lambda_along);
      EXPECT_LT(lambda_along, 0.25 * lo.min_match_information) << beams << " " << noise_m;
      EXPECT_GT(H(1, 1) * step_sd * step_sd, 10.0);  // across it the scan knows far more
    }
}

TEST(ScanMatcher, GeometricInformationSkipsNonFiniteReturns) {
  // A straight wall with one NaN return in it: the NaN neither joins its neighbours' wall nor
  // makes them corners; the information along the wall stays 0.
  std::vector<Eigen::Vector2d> wall;
  for (int k = -20; k <= 20; ++k) wall.emplace_back(0.05 * k, 2.0);
  const slam::LikelihoodField field(wall, 0.01, 0.1, 0.5, 0.3);
  const Eigen::Matrix3d clean = slam::geometricMatchInformation(field, wall, math::SE2(), 0.1, 0.3);
  wall[20] = Eigen::Vector2d(NAN, NAN);
  const Eigen::Matrix3d with_nan =
      slam::geometricMatchInformation(field, wall, math::SE2(), 0.1, 0.3);
  EXPECT_TRUE(with_nan.allFinite());
  EXPECT_NEAR(with_nan(0, 0), 0.0, 1e-9 * clean(1, 1));
  EXPECT_NEAR(with_nan(1, 1), clean(1, 1) * 40.0 / 41.0, 0.01 * clean(1, 1));
}

TEST(ScanMatcher, RecoversAKnownOffset) {
  const slam::LikelihoodField field(roomPoints(), 0.05, 0.1, 1.0);
  const math::SE2 truth(2.3, 1.7, 0.4);
  const std::vector<Eigen::Vector2d> scan = scanFrom(truth);
  ASSERT_GT(scan.size(), 150u);
  const slam::ScanMatcherConfig c;
  for (const math::SE2& off :
       {math::SE2(0.12, -0.08, 0.05), math::SE2(-0.2, 0.15, -0.15), math::SE2(0.0, 0.0, 0.0)}) {
    const math::SE2 prior(truth.x_m + off.x_m, truth.y_m + off.y_m, truth.yaw_rad + off.yaw_rad);
    const slam::ScanMatch m = slam::matchScan(field, scan, prior, c);
    EXPECT_NEAR(m.pose.x_m, truth.x_m, 0.01);
    EXPECT_NEAR(m.pose.y_m, truth.y_m, 0.01);
    EXPECT_NEAR(m.pose.yaw_rad, truth.yaw_rad, 0.003);
    EXPECT_GT(m.score, 0.95);
  }
  // Outside the window the match cannot reach the truth, but it does not get worse than the prior.
  const math::SE2 far(truth.x_m + 1.0, truth.y_m, truth.yaw_rad);
  const slam::ScanMatch m = slam::matchScan(field, scan, far, c);
  EXPECT_GE(m.score, field.score(scan, far));
}

TEST(LaserOdometry, RemovesAWheelOdometryBias) {
  // A drive across the room; the wheel odometry over-reads distance by 10% and turns 2% too much.
  slam::LaserOdometry lo;
  std::mt19937 rng(5);
  math::SE2 truth(1.0, 1.0, 0.0), odom = truth, prev = truth;
  double worst = 0.0, odom_err = 0.0;
  for (int k = 0; k < 120; ++k) {
    const math::SE2 next(1.0 + 0.06 * k, 1.0 + 0.005 * k,
                         0.3 * std::sin(0.05 * k));  // below the pillar
    const math::SE2 d = math::between(prev, next);
    odom = odom * math::SE2(1.1 * d.x_m, 1.1 * d.y_m, 1.02 * d.yaw_rad);
    prev = next;
    truth = next;
    const math::SE2 est = lo.add(scanFrom(truth, &rng, 0.01), odom);
    worst = std::max(worst, std::hypot(est.x_m - truth.x_m, est.y_m - truth.y_m));
    odom_err = std::hypot(odom.x_m - truth.x_m, odom.y_m - truth.y_m);
  }
  std::printf("laser odometry: worst error %.3f m; odometry alone %.3f m at the end\n", worst,
              odom_err);
  EXPECT_GT(odom_err, 0.5);  // the odometry alone drifts off
  EXPECT_LT(worst, 0.08);    // the matched poses stay within a few cm
  EXPECT_GT(lo.matched(), 110);
}

TEST(LaserOdometry, BridgesAnOdometryThatStallsAndThenJumps) {
  // The robot turns in place at 0.1 rad a scan; the wheel odometry stands still for 6 scans, then
  // catches up at once (0.7 rad in one increment), as the mit-csail log's does. From the odometry
  // alone the match would start 0.6 rad off, outside its 0.2 rad window.
  slam::LaserOdometry lo;
  std::mt19937 rng(7);
  double worst_yaw = 0.0;
  math::SE2 odom(2.0, 1.5, 0.0);
  for (int k = 0; k < 30; ++k) {
    const math::SE2 truth(2.0, 1.5, 0.1 * k);
    const bool stalled = k >= 10 && k < 16;
    if (!stalled) odom = math::SE2(2.0, 1.5, 0.1 * k);
    const math::SE2 est = lo.add(scanFrom(truth, &rng, 0.01), odom);
    worst_yaw = std::max(worst_yaw, std::fabs(math::angleDiff(est.yaw_rad, truth.yaw_rad)));
  }
  std::printf("laser odometry over a stalled odometry: worst yaw error %.4f rad\n", worst_yaw);
  // Fused with the stalled odometry the turn is lost (0.1 rad over the stall); from the jumped
  // odometry alone the match cannot reach the truth (0.6 rad).
  EXPECT_LT(worst_yaw, 0.02);
  EXPECT_EQ(lo.matched(), 29);
  EXPECT_GE(lo.odometryRejected(), 1);
}

TEST(LaserOdometry, KeepsASoundOdometryAgainstAWeakMatchThatTurns) {
  // The robot drives straight below the pillar with an exact odometry. On three scans (a crowd
  // walking past, say) more than half the points are clutter, and the room's points are turned
  // by 0.15 rad about the robot: the match finds that turn but explains only about a third of
  // the scan (score below odometry_gate_min_score), so the odometry is kept. The same scans with
  // the rule off (odometry_gate_min_score 0) turn the pose by the false 0.15 rad.
  auto run = [](double min_score, double* worst_yaw, long* weak) {
    slam::LaserOdometryConfig c;
    c.odometry_gate_min_score = min_score;
    slam::LaserOdometry lo(c);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-4.0, 4.0);
    *worst_yaw = 0.0;
    for (int k = 0; k < 40; ++k) {
      const math::SE2 truth(1.0 + 0.05 * k, 1.0, 0.0);
      std::vector<Eigen::Vector2d> scan = scanFrom(truth, &rng, 0.01);
      if (k >= 20 && k < 23) {
        const math::SE2 turn(0.0, 0.0, -0.15);
        for (auto& p : scan) p = turn.transformPoint(p);
        for (int j = 0; j < 300; ++j) scan.push_back({2.0 + std::fabs(u(rng)), u(rng)});
      }
      const math::SE2 est = lo.add(scan, truth);
      *worst_yaw = std::max(*worst_yaw, std::fabs(math::angleDiff(est.yaw_rad, truth.yaw_rad)));
    }
    *weak = lo.weakMatchesRejected();
  };
  double with_rule = 0.0, without_rule = 0.0;
  long weak_with = 0, weak_without = 0;
  run(slam::LaserOdometryConfig().odometry_gate_min_score, &with_rule, &weak_with);
  run(0.0, &without_rule, &weak_without);
  std::printf(
      "weak turning matches: worst yaw error %.4f rad with the rule (%ld kept the "
      "odometry), %.4f rad without\n",
      with_rule, weak_with, without_rule);
  EXPECT_GT(without_rule, 0.1);
  EXPECT_LT(with_rule, 0.01);
  EXPECT_GE(weak_with, 1);
  EXPECT_EQ(weak_without, 0);
}

TEST(LaserOdometry, DoesNotShrinkAFeaturelessCorridorAtTheEdgeOfTheSensorsReach) {
  // 40 m along a straight corridor 2 m wide with nothing on its walls, seen by a laser that
  // reaches 6 m, with an exact wheel odometry. The scans say nothing about the motion along the
  // corridor, so the laser odometry should keep the odometry's. But each scan newly sees a little
  // wall at the edge of the laser's reach, beyond the local map: matched, those points pull the
  // scan backwards, scan after scan. With the edge margin they are not matched; with degenerate
  // directions (the default) the motion along the corridor is the odometry's either way.
  const std::vector<adaptive_perception::test::Segment> walls{{{0, 0}, {100, 0}},
                                                              {{0, 2}, {100, 2}}};
  auto run = [&](double margin_m, double min_match_information) {
    slam::LaserOdometryConfig c;
    c.edge_margin_m = margin_m;
    c.min_match_information = min_match_information;
    slam::LaserOdometry lo(c);
    std::mt19937 rng(2);
    math::SE2 est;
    for (int k = 0; k <= 400; ++k) {  // 0.1 m a scan
      const math::SE2 truth(1.0 + 0.1 * k, 1.0, 0.0);
      est = lo.add(adaptive_perception::test::scanOf(walls, truth, &rng, 0.01, 6.0), truth);
    }
    return est.x_m - 41.0;
  };
  const slam::LaserOdometryConfig defaults;
  const double both = run(defaults.edge_margin_m, defaults.min_match_information);
  const double no_degenerate = run(defaults.edge_margin_m, 0.0);
  const double neither = run(0.0, 0.0);
  const double no_margin = run(0.0, defaults.min_match_information);
  std::printf(
      "40 m along a featureless corridor: laser odometry ends %.3f m off (defaults), %.3f m "
      "with the edge margin alone, %.3f m with degenerate directions alone, %.3f m with "
      "neither\n",
      both, no_degenerate, no_margin, neither);
  EXPECT_LT(std::fabs(both), 0.1);
  EXPECT_LT(std::fabs(no_degenerate), 0.1);
  EXPECT_LT(std::fabs(no_margin), 0.1);
  // Since the match's information is the scan's geometry, the fusion itself keeps the odometry
  // along the corridor (weight lambda / (1 + lambda), lambda about 0): with neither rule the scan
  // ends 0.04 m off here, where the Hessian's information lost 12.35 m.
  EXPECT_LT(std::fabs(both), std::fabs(neither));
}

// A drive through `walls` with a 180-degree laser reaching 8 m (1 cm noise), one scan per step of
// `truth`, the wheel odometry the true increments plus `kick` every tenth step. Returns the worst
// position and yaw errors of the laser odometry (and of the odometry alone) and the worst error
// along `free_dir` (a unit vector, map frame).
struct DriveErrors {
  double worst_m = 0.0, worst_rad = 0.0, worst_free_m = 0.0, odom_worst_m = 0.0;
  long rejected = 0;
  int most_degenerate = 0;
};
template <class Truth>
DriveErrors drive(const std::vector<adaptive_perception::test::Segment>& walls, Truth truth_at,
                  int steps, const math::SE2& kick, const Eigen::Vector2d& free_dir,
                  double min_match_information) {
  slam::LaserOdometryConfig c;
  c.min_match_information = min_match_information;
  slam::LaserOdometry lo(c);
  std::mt19937 rng(3);
  DriveErrors e;
  math::SE2 odom = truth_at(0);
  for (int k = 0; k <= steps; ++k) {
    const math::SE2 truth = truth_at(k);
    if (k > 0) {
      odom = odom * math::between(truth_at(k - 1), truth);
      if (k % 10 == 0) odom = odom * kick;
    }
    const math::SE2 est =
        lo.add(adaptive_perception::test::scanOf(walls, truth, &rng, 0.01, 8.0), odom);
    const Eigen::Vector2d err(est.x_m - truth.x_m, est.y_m - truth.y_m);
    e.worst_m = std::max(e.worst_m, err.norm());
    e.worst_free_m = std::max(e.worst_free_m, std::fabs(err.dot(free_dir)));
    e.worst_rad = std::max(e.worst_rad, std::fabs(math::angleDiff(est.yaw_rad, truth.yaw_rad)));
    e.odom_worst_m =
        std::max(e.odom_worst_m, std::hypot(odom.x_m - truth.x_m, odom.y_m - truth.y_m));
    e.most_degenerate = std::max(e.most_degenerate, lo.lastDegenerateDirections());
  }
  e.rejected = lo.odometryRejected();
  return e;
}

TEST(LaserOdometry, KeepsTheOdometryAlongABareCorridorWhenTheGateFires) {
  // 40 m along a straight featureless corridor 2 m wide; the wheel odometry is exact along it but
  // is kicked 0.2 m sideways every metre (a wheel sliding on a floor joint): the match sees the
  // kick across the corridor and the gate fires. Before, the pose then took the match alone, also
  // along the corridor, where the scan says nothing and the match lies anywhere in its window.
  // With the default min_match_information that direction is degenerate (its geometric
  // information is about 0) and keeps the exact odometry's motion; 0 is the match alone there.
  const std::vector<adaptive_perception::test::Segment> walls{{{0, 0}, {100, 0}},
                                                              {{0, 2}, {100, 2}}};
  const auto truth_at = [](int k) { return math::SE2(1.0 + 0.1 * k, 1.0, 0.0); };
  const math::SE2 kick(0.0, 0.2, 0.0);
  const DriveErrors now =
      drive(walls, truth_at, 400, kick, {1.0, 0.0}, slam::LaserOdometryConfig().min_match_information);
  const DriveErrors before = drive(walls, truth_at, 400, kick, {1.0, 0.0}, 0.0);
  std::printf(
      "bare corridor, odometry kicked sideways: worst error along it %.3f m (%.3f m overall, "
      "%ld gated) with degenerate directions, %.3f m (%.3f m, %ld gated) without; odometry "
      "alone %.3f m\n",
      now.worst_free_m, now.worst_m, now.rejected, before.worst_free_m, before.worst_m,
      before.rejected, now.odom_worst_m);
  EXPECT_LT(now.worst_free_m, 0.1);
  EXPECT_LT(now.worst_m, 0.3);
  EXPECT_GT(before.worst_free_m, 5.0 * now.worst_free_m);
  EXPECT_GE(now.rejected, 10);  // the gate fired: the case this test is about
  EXPECT_GE(now.most_degenerate, 1);
}

// A round hall (a 72-gon of radius 4.5 m), with and without a 1 m doorway, driven on a circle off
// its centre with an exact wheel odometry: every wall's normal passes (nearly) through the hall's
// centre, so the scan cannot tell a turn about it. Taken from the match there, the laser odometry
// turned away from the truth (4.4 m and 2.7-3.1 rad worst over 18 m); that direction's geometric
// information is about 0 (below 0.06 times the odometry's), so the pose keeps the odometry's turn.
TEST(LaserOdometry, KeepsTheOdometrysTurnInARoundHall) {
  const auto truth_at = [](int k) {  // a circle of radius 1.5 m about (0.8, 0), 0.09 m a step
    const double a = 0.06 * k;
    return math::SE2(0.8 + 1.5 * std::cos(a), 1.5 * std::sin(a), a + M_PI / 2);
  };
  for (double doorway_m : {0.0, 1.0}) {
    const auto walls = adaptive_perception::test::roundHall(4.5, 72, doorway_m);
    const DriveErrors now = drive(walls, truth_at, 200, math::SE2(), {0.0, 0.0},
                                  slam::LaserOdometryConfig().min_match_information);
    const DriveErrors before = drive(walls, truth_at, 200, math::SE2(), {0.0, 0.0}, 0.0);
    std::printf(
        "round hall (doorway %.1f m), exact odometry: worst error %.3f m, %.4f rad with "
        "degenerate directions, %.3f m, %.4f rad without\n",
        doorway_m, now.worst_m, now.worst_rad, before.worst_m, before.worst_rad);
    EXPECT_LT(now.worst_m, 0.1);
    if (doorway_m == 0.0) {
      EXPECT_LT(now.worst_rad, 0.02);
    } else {
      // With the doorway in view the turn is seen (its information 0.5-3.7 times the
      // odometry's), so it is fused, and the match's error there enters: 0.024 rad worst.
      EXPECT_LT(now.worst_rad, 0.5 * before.worst_rad);
    }
  }
}

TEST(ScanMatcher, RefusesBadSettings) {
  slam::ScanMatcherConfig c;
  c.resolution_m = 0.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  slam::LaserOdometryConfig l;
  l.local_map_keyframes = 0;
  EXPECT_THROW(slam::LaserOdometry{l}, std::invalid_argument);
  l = slam::LaserOdometryConfig();
  l.odometry_gate_min_score = 1.5;
  EXPECT_THROW(l.validate(), std::invalid_argument);
  l = slam::LaserOdometryConfig();
  l.min_match_information = -1.0;
  EXPECT_THROW(l.validate(), std::invalid_argument);
  l = slam::LaserOdometryConfig();
  l.connect_gap_m = 0.0;  // no walls through neighbouring returns: no information at all
  EXPECT_THROW(l.validate(), std::invalid_argument);
}

}  // namespace
