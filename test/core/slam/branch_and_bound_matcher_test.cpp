// The branch-and-bound search against scoring every lattice pose (written here independently:
// rotate, round each point to its cell, sum the field over the points), and a scan found again
// far outside the local matcher's window.
#include "adaptive_perception/slam/branch_and_bound_matcher.h"

#include <gtest/gtest.h>

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

struct Exhaustive {
  double score = -1.0;
  math::SE2 pose;
};

// The best lattice pose; with band_rad > 0, among the yaws more than band_rad from band_yaw.
Exhaustive exhaustive(const slam::LikelihoodField& f, const std::vector<Eigen::Vector2d>& pts,
                      const math::SE2& prior, const slam::BranchAndBoundWindow& w,
                      double band_yaw = 0.0, double band_rad = 0.0) {
  Exhaustive best;
  const double res = f.resolution();
  const int k = static_cast<int>(std::floor(w.search_xy_m / res + 1e-9));
  const int J = static_cast<int>(std::floor(w.search_yaw_rad / w.yaw_step_rad + 1e-9));
  const cv::Mat& v = f.values();
  for (int j = -J; j <= J; ++j) {
    const double yaw = prior.yaw_rad + j * w.yaw_step_rad;
    if (band_rad > 0.0 && std::fabs(math::angleDiff(yaw, band_yaw)) <= band_rad) continue;
    for (int oy = -k; oy <= k; ++oy)
      for (int ox = -k; ox <= k; ++ox) {
        double s = 0.0;
        for (const auto& p : pts) {
          const double wx = prior.x_m + std::cos(yaw) * p.x() - std::sin(yaw) * p.y();
          const double wy = prior.y_m + std::sin(yaw) * p.x() + std::cos(yaw) * p.y();
          const int cx = static_cast<int>(std::lround((wx - f.origin().x()) / res)) + ox;
          const int cy = static_cast<int>(std::lround((wy - f.origin().y()) / res)) + oy;
          if (cx >= 0 && cy >= 0 && cx < v.cols && cy < v.rows) s += v.at<float>(cy, cx);
        }
        s /= pts.size();
        if (s > best.score) best = {s, math::SE2(prior.x_m + ox * res, prior.y_m + oy * res, yaw)};
      }
  }
  return best;
}

TEST(BranchAndBoundMatcher, FindsTheSameBestScoreAsScoringEveryLatticePose) {
  // A coarse field (so that the exhaustive reference stays quick), scans from several poses with
  // noise, priors off by up to 1.5 m and 0.2 rad, and every depth from 0 (no pruning) to 5.
  const slam::LikelihoodField f(roomPoints(), 0.1, 0.15, 1.0);
  std::mt19937 rng(3);
  const slam::BranchAndBoundWindow w{2.0, 0.24, 0.04};
  const std::vector<math::SE2> truths = {{2.0, 1.5, 0.3}, {8.0, 4.5, 2.8}, {6.0, 2.0, -1.2}};
  const std::vector<math::SE2> offsets = {{1.5, -1.0, 0.2}, {-0.7, 1.3, -0.15}, {0.3, 0.2, 0.05}};
  for (size_t t = 0; t < truths.size(); ++t) {
    const auto scan = scanFrom(truths[t], &rng, 0.02);
    const math::SE2 prior(truths[t].x_m + offsets[t].x_m, truths[t].y_m + offsets[t].y_m,
                          truths[t].yaw_rad + offsets[t].yaw_rad);
    const Exhaustive ref = exhaustive(f, scan, prior, w);
    for (int depth = 0; depth <= 5; ++depth) {
      const slam::BranchAndBoundMatcher bnb(f, depth);
      long visited = 0;
      const auto m = bnb.match(scan, prior, w, 0.0, &visited);
      ASSERT_TRUE(m.has_value()) << t << " depth " << depth;
      EXPECT_NEAR(m->score, ref.score, 1e-5) << t << " depth " << depth;
      EXPECT_NEAR(m->pose.x_m, ref.pose.x_m, 1e-9) << t << " depth " << depth;
      EXPECT_NEAR(m->pose.y_m, ref.pose.y_m, 1e-9) << t << " depth " << depth;
      EXPECT_NEAR(math::angleDiff(m->pose.yaw_rad, ref.pose.yaw_rad), 0.0, 1e-9);
      // The lattice's best is within a cell and a yaw step of the truth.
      EXPECT_LT(std::hypot(m->pose.x_m - truths[t].x_m, m->pose.y_m - truths[t].y_m), 0.15) << t;
      EXPECT_LT(std::fabs(math::angleDiff(m->pose.yaw_rad, truths[t].yaw_rad)), 0.041) << t;
      if (depth >= 3) {  // the bound prunes: far fewer scores than the lattice's 41 x 41 x 13
        EXPECT_LT(visited, 41 * 41 * 13 / 4) << t << " depth " << depth;
      }
    }
  }
}

TEST(BranchAndBoundMatcher, ReturnsNothingBelowTheMinimumScore) {
  const slam::LikelihoodField f(roomPoints(), 0.1, 0.15, 1.0);
  const slam::BranchAndBoundMatcher bnb(f, 3);
  const auto scan = scanFrom({3.0, 3.0, 0.0});
  const slam::BranchAndBoundWindow w{1.0, 0.1, 0.02};
  const auto m = bnb.match(scan, {3.0, 3.0, 0.0}, w, 0.0);
  ASSERT_TRUE(m.has_value());
  EXPECT_FALSE(bnb.match(scan, {3.0, 3.0, 0.0}, w, m->score + 1e-3).has_value());
  // A scan placed entirely off the field scores 0 everywhere.
  EXPECT_FALSE(bnb.match(scan, {100.0, 100.0, 0.0}, w, 0.0).has_value());
}

TEST(BranchAndBoundMatcher, RecoversAPoseFarOutsideTheLocalWindow) {
  // After a long loop the estimate is metres and tens of degrees off: a 0.2 m / 0.05 cell field,
  // the prior 3.4 m and 0.5 rad away, a 4 m x 0.6 rad window (6.5 million lattice poses).
  const slam::LikelihoodField f(roomPoints(), 0.05, 0.1, 1.0);
  const slam::BranchAndBoundMatcher bnb(f, 5);
  std::mt19937 rng(5);
  const math::SE2 truth(2.5, 4.0, -0.6);
  const auto scan = scanFrom(truth, &rng, 0.02);
  long visited = 0;
  const auto m = bnb.match(scan, {5.5, 2.4, -0.1}, {4.0, 0.6, 0.01}, 0.3, &visited);
  ASSERT_TRUE(m.has_value());
  EXPECT_LT(std::hypot(m->pose.x_m - truth.x_m, m->pose.y_m - truth.y_m), 0.08);
  EXPECT_LT(std::fabs(math::angleDiff(m->pose.yaw_rad, truth.yaw_rad)), 0.011);
  EXPECT_GT(m->score, 0.7);
  EXPECT_LT(visited, 161L * 161 * 121 / 20);
}

TEST(BranchAndBoundMatcher, SearchesAFullTurnWithinItsBudget) {
  // A prior 2.6 rad off, a window of a full turn (pi either way): the same best as every lattice
  // pose. With max_bounds the search stops descending once it has computed that many bounds: at
  // least as many as it needed, the same answer; fewer than its top level, no descent at all.
  const slam::LikelihoodField f(roomPoints(), 0.1, 0.15, 1.0);
  const slam::BranchAndBoundMatcher bnb(f, 3);
  std::mt19937 rng(7);
  const math::SE2 truth(3.0, 2.0, 2.9);
  const auto scan = scanFrom(truth, &rng, 0.02);
  const math::SE2 prior(3.5, 2.4, 0.3);
  slam::BranchAndBoundWindow w{1.0, M_PI, 0.04};
  const Exhaustive ref = exhaustive(f, scan, prior, w);
  long visited = 0;
  const auto m = bnb.match(scan, prior, w, 0.0, &visited);
  ASSERT_TRUE(m.has_value());
  EXPECT_NEAR(m->score, ref.score, 1e-5);
  EXPECT_NEAR(math::angleDiff(m->pose.yaw_rad, ref.pose.yaw_rad), 0.0, 1e-9);
  EXPECT_LT(std::hypot(m->pose.x_m - truth.x_m, m->pose.y_m - truth.y_m), 0.15);
  EXPECT_LT(std::fabs(math::angleDiff(m->pose.yaw_rad, truth.yaw_rad)), 0.041);
  w.max_bounds = visited;
  long visited_budget = 0;
  const auto same = bnb.match(scan, prior, w, 0.0, &visited_budget);
  ASSERT_TRUE(same.has_value());
  EXPECT_EQ(same->score, m->score);
  EXPECT_LE(visited_budget, visited);
  // The top level: 157 yaws x 3 x 3 blocks of 8 cells over the 21 x 21 offsets.
  // Ambiguity in rotation against the exhaustive best of the yaws more than 0.3 rad from the
  // best's: ambiguous for a ratio below their scores' ratio, not above it (no budget: the second
  // descent shares the first's).
  w.max_bounds = 0;
  const Exhaustive rest = exhaustive(f, scan, prior, w, m->pose.yaw_rad, 0.3);
  ASSERT_GT(rest.score, 0.0);
  const double r = rest.score / m->score;
  std::printf("best %.3f, best turned more than 0.3 rad %.3f (ratio %.3f)\n", m->score, rest.score,
              r);
  for (const double ratio : {0.98 * r, 1.02 * r}) {
    const slam::RotationAmbiguity check{0.3, ratio};
    bool ambiguous = !(ratio < r);
    const auto again = bnb.match(scan, prior, w, 0.0, nullptr, &check, &ambiguous);
    ASSERT_TRUE(again.has_value());
    EXPECT_EQ(again->score, m->score);
    EXPECT_EQ(ambiguous, ratio < r) << ratio;
  }
  w.max_bounds = 1;
  long visited_top = 0;
  EXPECT_FALSE(bnb.match(scan, prior, w, 0.0, &visited_top).has_value());
  EXPECT_EQ(visited_top, 157L * 3 * 3);
  w.max_bounds = -1;
  EXPECT_THROW(bnb.match(scan, prior, w, 0.0), std::invalid_argument);
}

TEST(BranchAndBoundMatcher, RefusesBadArguments) {
  const slam::LikelihoodField f(roomPoints(), 0.1, 0.15, 1.0);
  EXPECT_THROW(slam::BranchAndBoundMatcher(f, -1), std::invalid_argument);
  EXPECT_THROW(slam::BranchAndBoundMatcher(f, 13), std::invalid_argument);
  const slam::BranchAndBoundMatcher bnb(f, 2);
  EXPECT_THROW(bnb.match(scanFrom({3, 3, 0}), {3, 3, 0}, {1.0, 0.1, 0.0}, 0.0),
               std::invalid_argument);
  EXPECT_FALSE(bnb.match({}, {3, 3, 0}, {1.0, 0.1, 0.01}, 0.0).has_value());
}

}  // namespace
