// Closed-form 2x2 symmetric eigenvalues: cases worked by hand, and Eigen's iterative solver on
// random matrices; the covariance test on each way a matrix can fail it.
#include "adaptive_perception/math/symmetric2.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <limits>
#include <random>

namespace math = adaptive_perception::math;

TEST(SymmetricEigenvalues, HandWorkedCases) {
  // diag(4, 1): 1 and 4. [[2, 1], [1, 2]]: 2 -+ 1. [[1, 2], [2, 1]]: -1 and 3 (indefinite).
  // [[1, 1], [1, 1]]: 0 and 2 (singular). [[0, 0], [0, 0]]: 0 and 0.
  const auto check = [](double a, double b, double d, double lo, double hi) {
    Eigen::Matrix2d m;
    m << a, b, b, d;
    const Eigen::Vector2d e = math::symmetricEigenvalues(m);
    EXPECT_NEAR(e[0], lo, 1e-14) << m;
    EXPECT_NEAR(e[1], hi, 1e-14) << m;
  };
  check(4, 0, 1, 1, 4);
  check(2, 1, 2, 1, 3);
  check(1, 2, 1, -1, 3);
  check(1, 1, 1, 0, 2);
  check(0, 0, 0, 0, 0);
  check(-3, 0, -5, -5, -3);
}

TEST(SymmetricEigenvalues, AgreesWithEigensIterativeSolver) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> scale(-6, 6);
  for (int i = 0; i < 2000; ++i) {
    const double s = std::pow(10.0, scale(rng));
    Eigen::Matrix2d m;
    m(0, 0) = s * u(rng);
    m(1, 1) = s * u(rng);
    m(0, 1) = m(1, 0) = s * u(rng);
    if (i % 2) m = m * m.transpose();  // half of them positive semi-definite
    const Eigen::Vector2d want = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(m).eigenvalues();
    const Eigen::Vector2d got = math::symmetricEigenvalues(m);
    const double tol = 1e-12 * m.cwiseAbs().maxCoeff();
    EXPECT_NEAR(got[0], want[0], tol) << m;
    EXPECT_NEAR(got[1], want[1], tol) << m;
  }
}

TEST(IsCovariance, RefusesEachWayOfNotBeingOne) {
  Eigen::Matrix2d c;
  c << 0.04, 0.001, 0.001, 0.0025;
  EXPECT_TRUE(math::isCovariance(c));
  EXPECT_TRUE(math::isCovariance(Eigen::Matrix2d::Zero()));  // a landmark known exactly
  Eigen::Matrix2d m = c;
  m(0, 1) = 0.002;  // not symmetric
  EXPECT_FALSE(math::isCovariance(m));
  m = c;
  m(0, 1) = m(1, 0) = 0.02;  // det < 0: indefinite
  EXPECT_FALSE(math::isCovariance(m));
  m = c;
  m(0, 0) = -0.04;
  EXPECT_FALSE(math::isCovariance(m));
  m = c;
  m(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(math::isCovariance(m));
  m = c;
  m(0, 0) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(math::isCovariance(m));
}
