// The total Fisher information (eq. 14) and its null space, on the monobot cases worked out in the
// paper (eqs. 17-18) and by the observability argument (H of rank n vs n + 1).
#include "adaptive_perception/slam/observability.h"

#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_perception/slam/monobot.h"

using namespace adaptive_perception;

// One-landmark monobot, H = [-1 1]: J = [1 -1; -1 1] sum 1/s_i (eq. 17), null space (1, 1)/sqrt 2.
TEST(Observability, OneLandmarkMonobotMatchesEquations17And18) {
  slam::FisherInformation fisher(2);
  Eigen::MatrixXd h(1, 2);
  h << -1.0, 1.0;
  double sum_inv = 0.0;
  for (double s : {0.5, 0.8, 1.3}) {
    fisher.add(h, Eigen::MatrixXd::Constant(1, 1, s));
    sum_inv += 1.0 / s;
  }
  Eigen::Matrix2d expected;
  expected << 1, -1, -1, 1;
  EXPECT_TRUE(fisher.matrix().isApprox(expected * sum_inv, 1e-12));
  const auto a = slam::analyzeInformation(fisher.matrix());
  EXPECT_EQ(a.rank, 1);
  ASSERT_EQ(a.null_space.cols(), 1);
  EXPECT_NEAR(std::fabs(a.null_space(0, 0)), 1.0 / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(a.null_space(0, 0), a.null_space(1, 0), 1e-9);
}

TEST(Observability, MismatchedSizesAreRejected) {
  slam::FisherInformation fisher(3);
  EXPECT_THROW(fisher.add(Eigen::MatrixXd::Ones(1, 2), Eigen::MatrixXd::Ones(1, 1)),
               std::invalid_argument);
  EXPECT_THROW(fisher.add(Eigen::MatrixXd::Ones(1, 3), -Eigen::MatrixXd::Ones(1, 1)),
               std::invalid_argument);
}

// Whole monobot runs: the standard model's Fisher information is singular (rank n of n + 1), the
// anchored and external ones are full rank.
TEST(Observability, MonobotFisherRankPerModel) {
  slam::MonobotConfig cfg;
  cfg.landmarks = 3;
  for (auto model : {slam::Variant::kStandard, slam::Variant::kAnchor, slam::Variant::kExternal}) {
    math::Rng rng(7);
    const auto run = slam::runMonobot(cfg, model, rng);
    const int rank = slam::analyzeInformation(run.fisher).rank;
    EXPECT_EQ(rank, model == slam::Variant::kStandard ? 3 : 4) << slam::variantName(model);
  }
}
