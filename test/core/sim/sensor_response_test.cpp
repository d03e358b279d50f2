// The shared sensor response (sim/sensor_response.h) against values worked by hand.
#include "adaptive_perception/sim/sensor_response.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "../refusal.h"

namespace adaptive_perception::sim {
namespace {

TEST(SensorResponse, LevelIsTheGammaCurveClippedTo8Bits) {
  SensorResponse s;
  s.gamma = 2.0;
  EXPECT_DOUBLE_EQ(s.level(0.0), 0.0);
  EXPECT_DOUBLE_EQ(s.level(1.0), 255.0);
  EXPECT_DOUBLE_EQ(s.level(0.25), 127.5);  // 255 * 0.25^(1/2)
  EXPECT_DOUBLE_EQ(s.level(2.0), 255.0);   // saturated
  EXPECT_DOUBLE_EQ(s.level(-0.5), 0.0);
  s.gamma = 1.0;
  EXPECT_DOUBLE_EQ(s.level(0.4), 102.0);
}

TEST(SensorResponse, NoiseGrowsWithTheSignal) {
  SensorResponse s;
  s.read_noise = 1.5;
  s.shot_noise = 0.05;
  EXPECT_DOUBLE_EQ(s.noiseSd(0.0), 1.5);
  EXPECT_DOUBLE_EQ(s.noiseSd(100.0), std::sqrt(2.25 + 5.0));
  EXPECT_DOUBLE_EQ(s.noiseSd(-20.0), 1.5);  // a level below zero adds no shot noise
}

TEST(SensorResponse, VignettingLosesItsFractionAtTheCorners) {
  SensorResponse s;
  s.vignetting = 0.4;
  EXPECT_DOUBLE_EQ(s.falloff(0.0), 1.0);
  EXPECT_DOUBLE_EQ(s.falloff(1.0), 0.6);
  EXPECT_DOUBLE_EQ(s.falloff(0.5), 0.8);
}

TEST(SensorResponse, ValidateNamesTheFieldOutOfRange) {
  EXPECT_NO_THROW(SensorResponse().validate());
  SensorResponse s;
  s.vignetting = 1.0;
  EXPECT_EQ(test_support::refusal([&] { s.validate(); }), "vignetting = 1 (allowed: [0, 1))");
  s = SensorResponse();
  s.gamma = 0.1;
  EXPECT_EQ(test_support::refusal([&] { s.validate(); }), "gamma = 0.1 (allowed: [0.5, 4])");
  s = SensorResponse();
  s.shot_noise = -1.0;
  EXPECT_EQ(test_support::refusal([&] { s.validate(); }), "shot_noise = -1 (allowed: >= 0)");
  s = SensorResponse();
  s.white_point_k = 500.0;
  EXPECT_EQ(test_support::refusal([&] { s.validate(); }),
            "white_point_k = 500 (allowed: [1000, 20000])");
}

}  // namespace
}  // namespace adaptive_perception::sim
