// The monobot study (Figs. 4-6) as Monte Carlo checks: the standard filter's final landmark error
// keeps the error of its initial conditions (the robot's start error, which no later observation
// can reveal: the unobservable direction), the anchored filter forgets it; all three are unbiased
// over runs.
#include "adaptive_perception/slam/monobot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../refusal.h"

using namespace adaptive_perception;

namespace {
struct Stats {
  double mean = 0.0, sd = 0.0, corr_first = 0.0;
};
Stats monteCarlo(slam::Variant model, int runs) {
  slam::MonobotConfig cfg;
  math::Rng rng(11);
  std::vector<double> fin, first;
  for (int r = 0; r < runs; ++r) {
    const auto run = slam::runMonobot(cfg, model, rng);
    fin.push_back(run.steps.back().est_landmark_m - cfg.landmark_m);
    first.push_back(-run.initial_robot_error_m);
  }
  Stats s;
  double mf = 0.0;
  for (size_t i = 0; i < fin.size(); ++i) {
    s.mean += fin[i] / runs;
    mf += first[i] / runs;
  }
  double cxy = 0.0, cxx = 0.0, cyy = 0.0;
  for (size_t i = 0; i < fin.size(); ++i) {
    cxy += (fin[i] - s.mean) * (first[i] - mf);
    cxx += (fin[i] - s.mean) * (fin[i] - s.mean);
    cyy += (first[i] - mf) * (first[i] - mf);
  }
  s.sd = std::sqrt(cxx / (runs - 1));
  s.corr_first = cxy / std::sqrt(cxx * cyy);
  return s;
}
}  // namespace

TEST(Monobot, StandardFinalErrorKeepsTheInitialErrorAnchoredDoesNot) {
  const int runs = 400;
  const Stats standard = monteCarlo(slam::Variant::kStandard, runs);
  const Stats anchor = monteCarlo(slam::Variant::kAnchor, runs);
  const Stats external = monteCarlo(slam::Variant::kExternal, runs);
  EXPECT_GT(standard.corr_first, 0.9);
  EXPECT_LT(std::fabs(anchor.corr_first), 0.5);
  EXPECT_LT(anchor.sd, standard.sd);
  EXPECT_LT(external.sd, standard.sd);
  // Unbiased: the mean error is within 4 standard errors of zero.
  for (const Stats& s : {standard, anchor, external})
    EXPECT_LT(std::fabs(s.mean), 4.0 * s.sd / std::sqrt(runs)) << s.mean << " sd " << s.sd;
}

TEST(Monobot, StandardLandmarkGainVanishes) {
  math::Rng rng(3);
  const auto run = slam::runMonobot(slam::MonobotConfig(), slam::Variant::kStandard, rng);
  // The landmark's own variance stops shrinking and its gain tends to zero.
  EXPECT_LT(std::fabs(run.steps.back().landmark_gain),
            0.05 * std::fabs(run.steps[1].landmark_gain));
  EXPECT_EQ(run.steps.size(), 101u);
  EXPECT_NEAR(run.steps.back().true_robot_m, -1.0, 0.2);
}

TEST(Monobot, BadConfigurationNamesTheField) {
  slam::MonobotConfig cfg;
  cfg.landmarks = 0;
  math::Rng rng(1);
  EXPECT_TRUE(test_support::refusedNaming(
      [&] { slam::runMonobot(cfg, slam::Variant::kStandard, rng); }, "landmarks"));
}
