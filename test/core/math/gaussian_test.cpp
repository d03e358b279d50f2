#include "adaptive_perception/math/gaussian.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

using adaptive_perception::math::Gaussian;
using adaptive_perception::math::Rng;

namespace {
Eigen::MatrixXd randomSpd(int n, Rng& rng) {
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = rng.gaussian();
  return a * a.transpose() + 0.5 * Eigen::MatrixXd::Identity(n, n);
}
}  // namespace

TEST(Gaussian, LogDensityMatchesClosedFormIn1D) {
  const Gaussian g(Eigen::VectorXd::Constant(1, 2.0), Eigen::MatrixXd::Constant(1, 1, 4.0));
  // N(3; 2, 4) = exp(-1/8) / sqrt(2 pi 4)
  EXPECT_NEAR(g.logDensity(Eigen::VectorXd::Constant(1, 3.0)),
              -0.125 - 0.5 * std::log(2 * M_PI * 4.0), 1e-12);
}

TEST(Gaussian, LogDensityMatchesExplicitInverseAndDeterminant) {
  Rng rng(1);
  for (int n : {2, 3, 6}) {
    const Eigen::MatrixXd s = randomSpd(n, rng);
    Eigen::VectorXd mu(n), x(n);
    for (int i = 0; i < n; ++i) {
      mu[i] = rng.gaussian();
      x[i] = rng.gaussian();
    }
    const double expect = -0.5 * (n * std::log(2 * M_PI) + std::log(s.determinant()) +
                                  (x - mu).dot(s.inverse() * (x - mu)));
    EXPECT_NEAR(Gaussian(mu, s).logDensity(x), expect, 1e-9);
  }
}

TEST(Gaussian, RejectsBadCovariance) {
  EXPECT_THROW(Gaussian(Eigen::VectorXd::Zero(2), Eigen::MatrixXd::Identity(3, 3)),
               std::invalid_argument);
  Eigen::MatrixXd not_pd(2, 2);
  not_pd << 1, 2, 2, 1;
  EXPECT_THROW(Gaussian(Eigen::VectorXd::Zero(2), not_pd), std::invalid_argument);
}

// The pose-with-covariance inputs of the nodes (initialpose, external_pose) are checked by this one
// function: a cross term written on one side only, a NaN cross term, and a matrix that is symmetric
// but not positive definite are each named; rviz's initial pose covariance passes.
TEST(Gaussian, CovarianceProblemNamesWhatIsWrong) {
  using adaptive_perception::math::covarianceProblem;
  Eigen::MatrixXd rviz = Eigen::Vector3d(0.25, 0.25, 0.068).asDiagonal();
  EXPECT_EQ(covarianceProblem(rviz), "");
  Eigen::MatrixXd one_sided = rviz;
  one_sided(2, 0) = 10.0;  // covariance[30] of a 6x6 message: yaw-x on one side only
  EXPECT_NE(covarianceProblem(one_sided).find("not symmetric (entry (2, 0) is 10"),
            std::string::npos)
      << covarianceProblem(one_sided);
  // Eigen's LLT reads the lower triangle only: it accepts a small one-sided term, which is how
  // such a covariance passed rbpf_localizer's check and then failed in the filter.
  Eigen::MatrixXd small_one_sided = rviz;
  small_one_sided(2, 0) = 0.1;
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(small_one_sided).info(), Eigen::Success);
  EXPECT_NE(covarianceProblem(small_one_sided).find("not symmetric"), std::string::npos);
  Eigen::MatrixXd nan_cross = rviz;
  nan_cross(2, 0) = nan_cross(0, 2) = std::nan("");
  EXPECT_NE(covarianceProblem(nan_cross).find("entry (0, 2) is nan"), std::string::npos)
      << covarianceProblem(nan_cross);
  Eigen::MatrixXd indefinite = rviz;
  indefinite(0, 1) = indefinite(1, 0) = 1.0;  // |rho| > 1
  EXPECT_EQ(covarianceProblem(indefinite), "is not positive definite");
  EXPECT_NE(covarianceProblem(Eigen::MatrixXd::Identity(2, 3)).find("not square"),
            std::string::npos);
  EXPECT_THROW(Gaussian(Eigen::VectorXd::Zero(3), one_sided), std::invalid_argument);
  EXPECT_THROW(Gaussian(Eigen::VectorXd::Zero(3), nan_cross), std::invalid_argument);
}

TEST(Gaussian, MarginalPicksTheBlock) {
  Rng rng(2);
  const Eigen::MatrixXd s = randomSpd(4, rng);
  Eigen::VectorXd mu(4);
  mu << 1, 2, 3, 4;
  const Gaussian m = Gaussian(mu, s).marginal({3, 1});
  EXPECT_DOUBLE_EQ(m.mean()[0], 4);
  EXPECT_DOUBLE_EQ(m.mean()[1], 2);
  EXPECT_DOUBLE_EQ(m.cov()(0, 1), s(3, 1));
  EXPECT_DOUBLE_EQ(m.cov()(1, 1), s(1, 1));
}

// Monte Carlo check of the conditional: among joint samples whose given component falls in a thin
// slab around the conditioning value, the others have the formula's mean and covariance.
TEST(Gaussian, ConditionalMatchesMonteCarlo) {
  Eigen::Vector3d mu(1.0, -1.0, 0.5);
  Eigen::Matrix3d s;
  s << 2.0, 0.8, 0.3, 0.8, 1.5, -0.4, 0.3, -0.4, 1.0;
  const Gaussian joint(mu, s);
  const double given = 1.4;  // x[2] = 1.4
  const Gaussian cond = joint.conditional({2}, Eigen::VectorXd::Constant(1, given));
  ASSERT_EQ(cond.dim(), 2);

  Rng rng(7);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d sum_sq = Eigen::Matrix2d::Zero();
  int n = 0;
  for (int i = 0; i < 2000000; ++i) {
    const Eigen::VectorXd x = joint.sample(rng);
    if (std::fabs(x[2] - given) > 0.02) continue;
    const Eigen::Vector2d y(x[0], x[1]);
    sum += y;
    sum_sq += y * y.transpose();
    ++n;
  }
  ASSERT_GT(n, 5000);
  const Eigen::Vector2d mc_mean = sum / n;
  const Eigen::Matrix2d mc_cov = sum_sq / n - mc_mean * mc_mean.transpose();
  // Standard error of the mean ~ sqrt(var / n) ~ 0.02; tolerance 4 standard errors.
  EXPECT_NEAR(mc_mean[0], cond.mean()[0], 4 * std::sqrt(cond.cov()(0, 0) / n));
  EXPECT_NEAR(mc_mean[1], cond.mean()[1], 4 * std::sqrt(cond.cov()(1, 1) / n));
  EXPECT_NEAR(mc_cov(0, 0), cond.cov()(0, 0), 0.05 * cond.cov()(0, 0));
  EXPECT_NEAR(mc_cov(1, 1), cond.cov()(1, 1), 0.05 * cond.cov()(1, 1));
  EXPECT_NEAR(mc_cov(0, 1), cond.cov()(0, 1), 0.05);
  // And the hand-computed value for component 0: mu0 + s02/s22 (given - mu2) = 1 + 0.3 * 0.9.
  EXPECT_NEAR(cond.mean()[0], 1.27, 1e-12);
  EXPECT_NEAR(cond.cov()(0, 0), 2.0 - 0.09, 1e-12);
}

TEST(Gaussian, SampleMomentsMatch) {
  Rng rng(11);
  const Eigen::MatrixXd s = randomSpd(3, rng);
  const Eigen::Vector3d mu(0.3, -2.0, 5.0);
  const Gaussian g(mu, s);
  const int n = 200000;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d x = g.sample(rng);
    sum += x;
    sum_sq += x * x.transpose();
  }
  const Eigen::Vector3d m = sum / n;
  const Eigen::Matrix3d c = sum_sq / n - m * m.transpose();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(m[i], mu[i], 4 * std::sqrt(s(i, i) / n));
  EXPECT_LT((c - s).norm() / s.norm(), 0.02);
}
