#include "adaptive_perception/math/se2.h"

#include <gtest/gtest.h>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/rng.h"

using adaptive_perception::math::between;
using adaptive_perception::math::kPi;
using adaptive_perception::math::Rng;
using adaptive_perception::math::SE2;
using adaptive_perception::math::wrapAngle;

TEST(Angles, WrapStaysInHalfOpenRange) {
  EXPECT_NEAR(wrapAngle(3 * kPi), -kPi, 1e-12);
  EXPECT_NEAR(wrapAngle(-3 * kPi), -kPi, 1e-12);
  EXPECT_NEAR(wrapAngle(kPi / 2 + 4 * kPi), kPi / 2, 1e-12);
  EXPECT_NEAR(wrapAngle(-0.1), -0.1, 1e-15);
  for (double a = -20.0; a < 20.0; a += 0.37) {
    const double w = wrapAngle(a);
    EXPECT_GE(w, -kPi);
    EXPECT_LT(w, kPi);
    EXPECT_NEAR(std::sin(w), std::sin(a), 1e-12);
    EXPECT_NEAR(std::cos(w), std::cos(a), 1e-12);
  }
}

TEST(SE2, ComposeMatchesHomogeneousMatrices) {
  Rng rng(3);
  for (int i = 0; i < 100; ++i) {
    const SE2 a{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-4, 4)};
    const SE2 b{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-4, 4)};
    const Eigen::Matrix3d m = a.matrix() * b.matrix();
    const SE2 c = a * b;
    EXPECT_NEAR(c.x_m, m(0, 2), 1e-12);
    EXPECT_NEAR(c.y_m, m(1, 2), 1e-12);
    EXPECT_NEAR(c.yaw_rad, std::atan2(m(1, 0), m(0, 0)), 1e-12);
  }
}

TEST(SE2, HandComputedComposition) {
  // Robot at (1, 2) facing +y moves 1 m forward and turns left 90 degrees: ends at (1, 3) facing
  // -x.
  const SE2 c = SE2(1, 2, kPi / 2) * SE2(1, 0, kPi / 2);
  EXPECT_NEAR(c.x_m, 1.0, 1e-12);
  EXPECT_NEAR(c.y_m, 3.0, 1e-12);
  EXPECT_NEAR(std::fabs(c.yaw_rad), kPi, 1e-12);
}

TEST(SE2, InverseAndBetween) {
  Rng rng(4);
  for (int i = 0; i < 100; ++i) {
    const SE2 a{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-4, 4)};
    const SE2 b{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-4, 4)};
    const SE2 id = a * a.inverse();
    EXPECT_NEAR(id.x_m, 0, 1e-12);
    EXPECT_NEAR(id.y_m, 0, 1e-12);
    EXPECT_NEAR(id.yaw_rad, 0, 1e-12);
    const SE2 back = a * between(a, b);
    EXPECT_NEAR(back.x_m, b.x_m, 1e-12);
    EXPECT_NEAR(back.y_m, b.y_m, 1e-12);
    EXPECT_NEAR(adaptive_perception::math::angleDiff(back.yaw_rad, b.yaw_rad), 0, 1e-12);
    const Eigen::Vector2d p{rng.uniform(-1, 1), rng.uniform(-1, 1)};
    const Eigen::Vector3d ph = a.matrix() * Eigen::Vector3d(p.x(), p.y(), 1.0);
    EXPECT_NEAR((a.transformPoint(p) - ph.head<2>()).norm(), 0, 1e-12);
  }
}
