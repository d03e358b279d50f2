#include "adaptive_perception/math/particle_set.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace adaptive_perception::math;

TEST(ParticleSet, NormalizeLogWeightsIsStableForHugeNegativeValues) {
  std::vector<double> w;
  const double log_norm = normalizeLogWeights({-1000.0, -1001.0, -1000.0 - std::log(2.0)}, &w);
  // Relative weights 1 : e^-1 : 1/2.
  const double z = 1.0 + std::exp(-1.0) + 0.5;
  EXPECT_NEAR(w[0], 1.0 / z, 1e-12);
  EXPECT_NEAR(w[1], std::exp(-1.0) / z, 1e-12);
  EXPECT_NEAR(w[2], 0.5 / z, 1e-12);
  EXPECT_NEAR(log_norm, -1000.0 + std::log(z), 1e-9);
}

TEST(ParticleSet, AllImpossibleGivesUniform) {
  std::vector<double> w;
  const double inf = std::numeric_limits<double>::infinity();
  normalizeLogWeights({-inf, -inf, std::nan("")}, &w);
  for (double x : w) EXPECT_DOUBLE_EQ(x, 1.0 / 3.0);
}

TEST(ParticleSet, EffectiveSampleSize) {
  EXPECT_DOUBLE_EQ(effectiveSampleSize({0.25, 0.25, 0.25, 0.25}), 4.0);
  EXPECT_DOUBLE_EQ(effectiveSampleSize({1.0, 0.0, 0.0}), 1.0);
  EXPECT_NEAR(effectiveSampleSize({0.5, 0.5, 0.0}), 2.0, 1e-12);
}

// Every scheme keeps the expected number of copies of particle i equal to N w_i.
TEST(ParticleSet, ResamplingPreservesExpectedCounts) {
  const std::vector<double> w = {0.05, 0.4, 0.0, 0.15, 0.3, 0.1};
  const std::size_t n = 50;
  for (auto scheme : {ResamplingScheme::kMultinomial, ResamplingScheme::kStratified,
                      ResamplingScheme::kSystematic}) {
    Rng rng(5);
    std::vector<double> counts(w.size(), 0.0);
    const int trials = 20000;
    for (int t = 0; t < trials; ++t)
      for (std::size_t i : resampleIndices(w, n, scheme, rng)) counts[i] += 1.0;
    for (std::size_t i = 0; i < w.size(); ++i) {
      // Multinomial count variance N w (1 - w) per trial: the mean over trials has sd sqrt(that /
      // trials).
      const double sd = std::sqrt(n * w[i] * (1 - w[i]) / trials) + 1e-9;
      EXPECT_NEAR(counts[i] / trials, n * w[i], 5 * sd)
          << "scheme " << static_cast<int>(scheme) << " i " << i;
    }
    EXPECT_EQ(counts[2], 0.0);  // a zero-weight particle never survives
  }
}

TEST(ParticleSet, SystematicCountsAreFloorOrCeil) {
  const std::vector<double> w = {0.123, 0.377, 0.2, 0.3};
  Rng rng(9);
  for (int t = 0; t < 1000; ++t) {
    std::vector<int> c(w.size(), 0);
    for (std::size_t i : resampleIndices(w, 10, ResamplingScheme::kSystematic, rng)) ++c[i];
    for (std::size_t i = 0; i < w.size(); ++i) {
      EXPECT_GE(c[i], static_cast<int>(std::floor(10 * w[i])));
      EXPECT_LE(c[i], static_cast<int>(std::ceil(10 * w[i])));
    }
  }
}

TEST(ParticleSet, ResampleReplacesStatesAndResetsWeights) {
  ParticleSet<int> set({10, 20, 30});
  set.setLogWeights(
      {-std::numeric_limits<double>::infinity(), 0.0, -std::numeric_limits<double>::infinity()});
  Rng rng(1);
  set.resample(ResamplingScheme::kSystematic, rng, 5);
  ASSERT_EQ(set.size(), 5u);
  for (int s : set.states()) EXPECT_EQ(s, 20);
  for (double w : set.weights()) EXPECT_DOUBLE_EQ(w, 0.2);
}

TEST(ParticleSet, ParseScheme) {
  EXPECT_EQ(parseResamplingScheme("low_variance"), ResamplingScheme::kSystematic);
  EXPECT_THROW(parseResamplingScheme("bogus"), std::invalid_argument);
}
