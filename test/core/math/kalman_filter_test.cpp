#include "adaptive_perception/math/kalman_filter.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

#include "adaptive_perception/math/gaussian.h"

using adaptive_perception::math::Gaussian;
using adaptive_perception::math::KalmanFilter;
using adaptive_perception::math::Rng;
using adaptive_perception::math::selectionMatrix;

namespace {
Eigen::MatrixXd randomSpd(int n, Rng& rng, double ridge = 0.5) {
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = rng.gaussian();
  return a * a.transpose() + ridge * Eigen::MatrixXd::Identity(n, n);
}
Eigen::VectorXd randomVec(int n, Rng& rng) {
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = rng.gaussian();
  return v;
}
}  // namespace

TEST(KalmanFilter, JosephAndStandardFormsAgree) {
  Rng rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 6, m = 4;
    const Eigen::MatrixXd p = randomSpd(n, rng), q = randomSpd(m, rng);
    Eigen::MatrixXd h(m, n);
    for (int i = 0; i < m; ++i) h.row(i) = randomVec(n, rng).transpose();
    const Eigen::VectorXd mu = randomVec(n, rng), z = randomVec(m, rng);
    KalmanFilter a(mu, p), b(mu, p);
    const auto ra = a.update(h, z, q);
    const auto rb = b.updateStandardForm(h, z, q);
    EXPECT_LT((a.mean() - b.mean()).norm(), 1e-9);
    EXPECT_LT((a.cov() - b.cov()).norm(), 1e-9 * p.norm());
    EXPECT_NEAR(ra.log_likelihood, rb.log_likelihood, 1e-12);
  }
}

// A sequence of KF updates on a static state equals the batch Gaussian posterior computed in
// information form: P^-1 = P0^-1 + sum H^T Q^-1 H, P^-1 mu = P0^-1 mu0 + sum H^T Q^-1 z.
TEST(KalmanFilter, SequentialUpdatesEqualBatchPosterior) {
  Rng rng(2);
  const int n = 3;
  const Eigen::MatrixXd p0 = randomSpd(n, rng);
  const Eigen::VectorXd mu0 = randomVec(n, rng);
  KalmanFilter kf(mu0, p0);
  Eigen::MatrixXd info = p0.inverse();
  Eigen::VectorXd info_vec = info * mu0;
  double total_ll = 0.0;
  for (int k = 0; k < 10; ++k) {
    const int m = 1 + k % 3;
    Eigen::MatrixXd h(m, n);
    for (int i = 0; i < m; ++i) h.row(i) = randomVec(n, rng).transpose();
    const Eigen::MatrixXd q = randomSpd(m, rng, 0.2);
    const Eigen::VectorXd z = randomVec(m, rng);
    total_ll += kf.update(h, z, q).log_likelihood;
    info += h.transpose() * q.inverse() * h;
    info_vec += h.transpose() * q.inverse() * z;
  }
  const Eigen::MatrixXd p_batch = info.inverse();
  EXPECT_LT((kf.cov() - p_batch).norm(), 1e-9);
  EXPECT_LT((kf.mean() - p_batch * info_vec).norm(), 1e-9);
  EXPECT_TRUE(std::isfinite(total_ll));
}

// Observing components directly equals conditioning the joint Gaussian of (state, observation).
TEST(KalmanFilter, PartialObservationEqualsConditioning) {
  Rng rng(3);
  const int n = 6;
  const Eigen::MatrixXd p = randomSpd(n, rng);
  const Eigen::VectorXd mu = randomVec(n, rng);
  const std::vector<int> obs = {4, 1};
  const Eigen::MatrixXd q = 0.3 * Eigen::MatrixXd::Identity(2, 2);
  const Eigen::VectorXd z = randomVec(2, rng);

  KalmanFilter kf(mu, p);
  const auto res = kf.updatePartial(obs, z, q);

  // Joint of x (n) and z = H x + v (2): mean [mu; H mu], cov [[P, P H^T], [H P, H P H^T + Q]].
  const Eigen::MatrixXd h = selectionMatrix(n, obs);
  Eigen::MatrixXd joint_cov(n + 2, n + 2);
  joint_cov << p, p * h.transpose(), h * p, h * p * h.transpose() + q;
  Eigen::VectorXd joint_mean(n + 2);
  joint_mean << mu, h * mu;
  const Gaussian joint(joint_mean, joint_cov);
  const Gaussian cond = joint.conditional({n, n + 1}, z);
  EXPECT_LT((cond.mean() - kf.mean()).norm(), 1e-10);
  EXPECT_LT((cond.cov() - kf.cov()).norm(), 1e-10);
  // The innovation likelihood is the marginal density of z.
  EXPECT_NEAR(res.log_likelihood, joint.marginal({n, n + 1}).logDensity(z), 1e-10);
}

TEST(KalmanFilter, NoiselessPartialObservationPinsObservedAndMovesCorrelated) {
  Eigen::Matrix2d p;
  p << 1.0, 0.9, 0.9, 1.0;
  KalmanFilter kf(Eigen::Vector2d(0, 0), p);
  kf.updatePartial({0}, Eigen::VectorXd::Constant(1, 2.0), Eigen::MatrixXd::Constant(1, 1, 1e-12));
  EXPECT_NEAR(kf.mean()[0], 2.0, 1e-9);
  EXPECT_NEAR(kf.mean()[1], 1.8, 1e-9);  // regression slope 0.9
  EXPECT_NEAR(kf.cov()(1, 1), 1.0 - 0.81, 1e-9);
}

TEST(KalmanFilter, PredictAddsDriftAndAppliesTransition) {
  KalmanFilter kf(Eigen::Vector2d(1, 2), Eigen::Matrix2d::Identity());
  kf.predict(0.5 * Eigen::Matrix2d::Identity());
  EXPECT_DOUBLE_EQ(kf.cov()(0, 0), 1.5);
  Eigen::Matrix2d a;
  a << 1, 1, 0, 1;  // constant velocity
  kf.predict(a, Eigen::Matrix2d::Zero());
  EXPECT_DOUBLE_EQ(kf.mean()[0], 3.0);
  EXPECT_DOUBLE_EQ(kf.cov()(0, 0), 3.0);
  EXPECT_DOUBLE_EQ(kf.cov()(0, 1), 1.5);
}

TEST(KalmanFilter, RejectsMismatchedSizes) {
  KalmanFilter kf(Eigen::Vector2d(0, 0), Eigen::Matrix2d::Identity());
  EXPECT_THROW(kf.update(Eigen::MatrixXd::Identity(3, 3), Eigen::VectorXd::Zero(3),
                         Eigen::MatrixXd::Identity(3, 3)),
               std::invalid_argument);
  EXPECT_THROW(kf.predict(Eigen::MatrixXd::Identity(3, 3)), std::invalid_argument);
  EXPECT_THROW(kf.updatePartial({5}, Eigen::VectorXd::Zero(1), Eigen::MatrixXd::Identity(1, 1)),
               std::out_of_range);
}
