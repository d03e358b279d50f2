#include "adaptive_perception/math/log_add.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace am = adaptive_perception::math;

// Against the closed form with libm, on a fine sweep that falls between the table's knots.
TEST(LogAdd, MatchesTheClosedFormWithinItsBound) {
  double worst = 0.0;
  for (double x = 0.0; x < 50.0; x += 0.0013) {
    const double exact = std::log1p(std::exp(-x));
    worst = std::max(worst, std::fabs(am::log1pExpNeg(x) - exact));
  }
  EXPECT_LE(worst, am::kLogAddMaxError);
  EXPECT_GT(worst, 0.0);  // it is an approximation: the bound is what is promised
}

TEST(LogAdd, AddsProbabilities) {
  // log(0.2 + 0.3) from log 0.2 and log 0.3, either order.
  EXPECT_NEAR(am::logAddExp(std::log(0.2), std::log(0.3)), std::log(0.5), am::kLogAddMaxError);
  EXPECT_NEAR(am::logAddExp(std::log(0.3), std::log(0.2)), std::log(0.5), am::kLogAddMaxError);
  // Equal terms: log 2 exactly (a knot of the table).
  EXPECT_DOUBLE_EQ(am::logAddExp(-7.0, -7.0), -7.0 + std::log(2.0));
  // Far apart: the larger.
  EXPECT_DOUBLE_EQ(am::logAddExp(-3.0, -300.0), -3.0);
}

TEST(LogAdd, MinusInfinityIsZeroProbability) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_DOUBLE_EQ(am::logAddExp(-inf, -2.5), -2.5);
  EXPECT_DOUBLE_EQ(am::logAddExp(-2.5, -inf), -2.5);
  EXPECT_EQ(am::logAddExp(-inf, -inf), -inf);
  EXPECT_DOUBLE_EQ(am::log1pExpNeg(inf), 0.0);
}

TEST(LogAdd, ANaNIsNotHidden) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(am::log1pExpNeg(nan)));
  EXPECT_TRUE(std::isnan(am::logAddExp(-1.0, nan)));
  EXPECT_TRUE(std::isnan(am::logAddExp(nan, -1.0)));
}
