// The CONDENSATION colour-distribution state (papers/001 section 3.3): principal components,
// the warp's preserved quantities (mass, centroid, principal magnitudes, turned axes), the
// alignment angles, and the learning of the dynamics A, B from a sequence made with known ones.
#include "adaptive_perception/tracking/color_distribution.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/tracking/dynamics.h"

using namespace adaptive_perception;
using namespace adaptive_perception::tracking;

namespace {
ColorPoints anisotropicCloud(int n, std::uint64_t seed) {
  math::Rng rng(seed);
  const Eigen::Matrix3f r =
      Eigen::AngleAxisf(0.4f, Eigen::Vector3f(1, 2, 0.5).normalized()).toRotationMatrix();
  ColorPoints pts;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3f z{0.08f * float(rng.gaussian()), 0.03f * float(rng.gaussian()),
                            0.01f * float(rng.gaussian())};
    pts.push_back(Eigen::Vector3f(0.6f, 0.3f, 0.4f) + r * z);
  }
  return pts;
}
}  // namespace

TEST(ColorStats, PrincipalComponentsOfAKnownCloud) {
  const ColorPoints pts = anisotropicCloud(20000, 1);
  const ColorStats s = colorStats(pts);
  EXPECT_NEAR(s.mean.x(), 0.6, 2e-3);
  EXPECT_NEAR(s.magnitudes[0], 0.08, 2e-3);
  EXPECT_NEAR(s.magnitudes[1], 0.03, 1e-3);
  EXPECT_NEAR(s.magnitudes[2], 0.01, 5e-4);
  EXPECT_NEAR(s.axes.determinant(), 1.0, 1e-9);
  EXPECT_NEAR((s.axes.transpose() * s.axes - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-9);
  EXPECT_THROW(colorStats({}), std::invalid_argument);
}

TEST(Warp, PreservesMassAndSetsCentroidMagnitudesAndTurn) {
  const ColorPoints ref = anisotropicCloud(5000, 2);
  const ColorStats rs = colorStats(ref);
  // Identity state: the same points.
  const ColorPoints same = warpDistribution(ref, rs, stateOf(rs));
  ASSERT_EQ(same.size(), ref.size());
  for (size_t i = 0; i < ref.size(); i += 97) EXPECT_LT((same[i] - ref[i]).norm(), 1e-5);
  // A new centroid, magnitudes and a turn of (0.3, -0.2).
  DistributionState x;
  x << 0.4, 0.5, 0.45, 0.05, 0.04, 0.02, 0.3, -0.2;
  const ColorPoints w = warpDistribution(ref, rs, x);
  ASSERT_EQ(w.size(), ref.size());  // mass
  const ColorStats ws = colorStats(w);
  EXPECT_NEAR((ws.mean - x.head<3>()).norm(), 0.0, 1e-5);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(ws.magnitudes[k], x[3 + k], 1e-4);
  // The warped first axis is the reference's turned by the state's angles, and the angles read
  // back from the two sets of axes are the state's.
  const Eigen::Vector3d turned = alignmentRotation(rs.axes, 0.3, -0.2) * rs.axes.col(0);
  EXPECT_NEAR(std::abs(turned.dot(ws.axes.col(0))), 1.0, 1e-6);
  const Eigen::Vector2d ang = alignmentAngles(rs.axes, ws.axes);
  EXPECT_NEAR(ang[0], 0.3, 1e-4);
  EXPECT_NEAR(ang[1], -0.2, 1e-4);
}

TEST(Dynamics, LearnsKnownAAndBFromASequence) {
  // A damped oscillation per dimension with known coefficients and noise.
  Ar2Model truth;
  truth.a1.setZero();
  truth.a0.setZero();
  for (int k = 0; k < kStateDim; ++k) {
    truth.a1(k, k) = 1.6 - 0.05 * k;
    truth.a0(k, k) = -0.7 + 0.02 * k;
    truth.d[k] = 0.01 * (k + 1);
    truth.b(k, k) = 0.02 + 0.01 * k;
  }
  math::Rng rng(3);
  std::vector<DistributionState> seq(2, DistributionState::Zero());
  for (int t = 0; t < 60000; ++t)
    seq.push_back(truth.sample(seq[seq.size() - 1], seq[seq.size() - 2], rng));
  for (bool diagonal : {true, false}) {
    const Ar2Model m = learnAr2(seq, diagonal);
    for (int k = 0; k < kStateDim; ++k) {
      EXPECT_NEAR(m.a1(k, k), truth.a1(k, k), 0.02) << "diagonal " << diagonal << " dim " << k;
      EXPECT_NEAR(m.a0(k, k), truth.a0(k, k), 0.02);
      EXPECT_NEAR(m.b(k, k), truth.b(k, k), 0.03 * truth.b(k, k));
    }
    if (!diagonal) {
      EXPECT_LT((m.a1 - truth.a1).cwiseAbs().maxCoeff(), 0.03);
    }
  }
  EXPECT_THROW(learnAr2(std::vector<DistributionState>(10)), std::invalid_argument);
  // Constant velocity continues a straight line exactly.
  const Ar2Model cv = Ar2Model::constantVelocity(DistributionState::Zero());
  DistributionState x0 = DistributionState::Constant(1.0), x1 = DistributionState::Constant(1.5);
  EXPECT_NEAR((cv.mean(x1, x0) - DistributionState::Constant(2.0)).norm(), 0.0, 1e-12);
}

TEST(Dynamics, YamlRoundTripAndClearErrors) {
  const std::string dir = testing::TempDir() + "/dyn_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  Ar2Model m = Ar2Model::constantVelocity(DistributionState::Constant(0.25));
  m.d[3] = -0.125;
  m.saveYaml(dir + "/d.yaml");
  const Ar2Model back = Ar2Model::loadYaml(dir + "/d.yaml");
  EXPECT_EQ((back.a1 - m.a1).norm(), 0.0);
  EXPECT_EQ((back.b - m.b).norm(), 0.0);
  EXPECT_EQ(back.d[3], -0.125);
  std::ofstream(dir + "/bad.yaml") << "a1: [1, 2]\n";
  try {
    Ar2Model::loadYaml(dir + "/bad.yaml");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Ar2Model::loadYaml(dir + "/missing.yaml"), std::runtime_error);
  std::filesystem::remove_all(dir);
}
