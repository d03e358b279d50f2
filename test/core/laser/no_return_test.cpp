// NoReturnFinder against scans built by hand: a sensor that writes 50.00 m for "no return" under a
// stated range_max of 81.9 m, a real far wall whose returns spread, and the bounds of the rule.
#include "adaptive_perception/laser/no_return.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace laser = adaptive_perception::laser;

namespace {

// 181 readings: walls between 2 and 8 m, and `no_returns` of them written as `no_return_m`.
std::vector<float> scan(int no_returns, float no_return_m, std::mt19937* rng) {
  std::uniform_real_distribution<float> wall(2.0f, 8.0f);
  std::vector<float> r(181);
  for (int i = 0; i < 181; ++i) r[i] = i < no_returns ? no_return_m : wall(*rng);
  return r;
}

}  // namespace

TEST(NoReturnFinder, FindsAValueWrittenForNoReturnBelowTheStatedMaximum) {
  laser::NoReturnFinder finder;
  std::mt19937 rng(1);
  finder.add(scan(6, 50.0f, &rng), 81.9);  // 6 < min_count 10: not yet
  EXPECT_FALSE(finder.value());
  std::vector<float> s = scan(6, 50.0f, &rng);
  EXPECT_EQ(finder.apply(&s), 0);
  bool found_now = false;
  EXPECT_EQ(finder.mark(&s, 81.9, &found_now), 6);  // 12 readings at exactly 50.0, none below
  EXPECT_TRUE(found_now);
  ASSERT_TRUE(finder.value());
  EXPECT_FLOAT_EQ(*finder.value(), 50.0f);
  EXPECT_EQ(finder.readingsAtValue(), 12);
  // Readings from 49.9 m (the margin) on become +inf; the walls stay.
  std::vector<float> next{3.0f, 49.85f, 49.95f, 50.0f, 7.5f};
  EXPECT_EQ(finder.apply(&next), 2);
  EXPECT_FLOAT_EQ(next[0], 3.0f);
  EXPECT_FLOAT_EQ(next[1], 49.85f);
  EXPECT_TRUE(std::isinf(next[2]) && next[2] > 0);
  EXPECT_TRUE(std::isinf(next[3]) && next[3] > 0);
  EXPECT_FLOAT_EQ(next[4], 7.5f);
}

TEST(NoReturnFinder, AFarWallWhoseReturnsSpreadIsNotANoReturn) {
  // A wall at 30 m seen many times: its returns spread over +-3 cm, and the farthest value, even
  // repeated (millimetre readings), has more readings in the metre below it.
  laser::NoReturnFinder finder;
  std::mt19937 rng(2);
  std::normal_distribution<float> far(30.0f, 0.01f);
  for (int k = 0; k < 50; ++k) {
    std::vector<float> s = scan(0, 0.0f, &rng);
    for (int i = 0; i < 40; ++i) s[i] = std::round(far(rng) * 100.0f) / 100.0f;  // cm steps
    finder.add(s, 81.9);
  }
  EXPECT_FALSE(finder.value());
}

TEST(NoReturnFinder, ReadingsAtOrBeyondTheStatedMaximumAreNotCounted) {
  // A sensor whose no-returns are at its stated range_max needs no inference: validPoints already
  // drops them; and they must not make a value either.
  laser::NoReturnFinder finder;
  std::mt19937 rng(3);
  for (int k = 0; k < 5; ++k) finder.add(scan(30, 30.0f, &rng), 30.0);
  EXPECT_FALSE(finder.value());
  std::vector<float> weird{NAN, -1.0f, INFINITY, 0.0f};
  finder.add(weird, 30.0);
  EXPECT_FALSE(finder.value());
}

TEST(NoReturnFinder, RefusesBadSettings) {
  laser::NoReturnConfig c;
  c.min_count = 0;
  EXPECT_THROW(laser::NoReturnFinder{c}, std::invalid_argument);
  c = laser::NoReturnConfig();
  c.gap_m = 0.0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = laser::NoReturnConfig();
  c.margin_m = NAN;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}
