// The Kuemmerle et al. relations metric on a hand-computed case, and the relations file reader.
#include "adaptive_perception/slam/relations.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

using namespace adaptive_perception;

// Truth: (0,0,0) -> (1,0,0). Estimate: (0,0,0) -> (1.1, 0, 0.1). The relation says delta* =
// (1, 0, 0); the estimated delta is (1.1, 0, 0.1); error = between(delta*, delta) = (0.1, 0, 0.1).
// A second relation (t=1 -> t=2) with truth (0, 1, pi/2) and estimate from (1.1,0,0.1) to
// (1.1, 1, 0.1 + pi/2): estimated delta = R(-0.1) (0, 1) = (sin 0.1, cos 0.1), rotation pi/2.
TEST(Relations, HandComputedErrors) {
  std::map<double, math::SE2> est{{0.0, math::SE2(0, 0, 0)},
                                  {1.0, math::SE2(1.1, 0, 0.1)},
                                  {2.0, math::SE2(1.1, 1.0, 0.1 + M_PI / 2)}};
  const std::vector<slam::Relation> rel{{0.0, 1.0, math::SE2(1, 0, 0)},
                                        {1.0, 2.0, math::SE2(0, 1, M_PI / 2)},
                                        {5.0, 6.0, math::SE2(0, 0, 0)}};
  const auto e = slam::evaluateRelations(rel, est, 0.01);
  EXPECT_EQ(e.used, 2);
  EXPECT_EQ(e.skipped, 1);
  const double t2 = std::hypot(std::sin(0.1), std::cos(0.1) - 1.0);
  EXPECT_NEAR(e.trans_mean_m, 0.5 * (0.1 + t2), 1e-12);
  EXPECT_NEAR(e.trans_std_m, 0.5 * std::fabs(0.1 - t2), 1e-12);
  EXPECT_NEAR(e.rot_mean_rad, 0.05, 1e-12);
  EXPECT_NEAR(e.rot_std_rad, 0.05, 1e-12);
}

TEST(Relations, FileRoundTripAndErrorsNameTheLine) {
  const std::string path = testing::TempDir() + "/relations_test.relations";
  slam::writeRelations(path, {{1.5, 2.5, math::SE2(0.3, -0.2, 0.1)}});
  const auto r = slam::readRelations(path);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_DOUBLE_EQ(r[0].t2_s, 2.5);
  EXPECT_DOUBLE_EQ(r[0].delta.y_m, -0.2);
  EXPECT_NEAR(r[0].delta.yaw_rad, 0.1, 1e-12);  // written with 12 significant digits
  {
    std::ofstream f(path);
    f << "# comment\n1 2 0 0 0 0 0 0\n1 2 0 x 0 0 0 0\n";
  }
  try {
    slam::readRelations(path);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(":3:"), std::string::npos) << e.what();
  }
  {
    std::ofstream f(path);
    f << "1 2 0 0 0 0 0\n";
  }
  EXPECT_THROW(slam::readRelations(path), std::runtime_error);
  EXPECT_THROW(slam::readRelations(path + ".missing"), std::runtime_error);
  std::remove(path.c_str());
}

// Relations drawn from a trajectory evaluate to zero error on that same trajectory.
TEST(Relations, RelationsFromTruthGiveZeroErrorOnTruth) {
  std::map<double, math::SE2> truth;
  for (int i = 0; i < 50; ++i) truth[0.1 * i] = math::SE2(0.05 * i, std::sin(0.1 * i), 0.02 * i);
  const auto rel = slam::relationsFromTrajectory(truth, 0.5, 20, 3);
  EXPECT_GT(rel.size(), 20u);
  const auto e = slam::evaluateRelations(rel, truth, 1e-6);
  EXPECT_EQ(e.skipped, 0);
  EXPECT_NEAR(e.trans_mean_m, 0.0, 1e-12);
  EXPECT_NEAR(e.rot_mean_rad, 0.0, 1e-12);
}
