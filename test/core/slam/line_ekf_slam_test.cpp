// Line-landmark EKF SLAM: Jacobians against central differences, the inverse observation, the
// Joseph update against the textbook update, JCBB against nearest neighbour.
#include "adaptive_perception/slam/line_ekf_slam.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "../refusal.h"
#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/kalman_filter.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/slam/map_io.h"

using namespace adaptive_perception;
using slam::Line;

namespace {

Eigen::Vector2d vec(const Line& l) { return Eigen::Vector2d(l.rho_m, l.alpha_rad); }
Eigen::Vector3d vec(const math::SE2& p) { return Eigen::Vector3d(p.x_m, p.y_m, p.yaw_rad); }

template <typename F>
Eigen::MatrixXd numericJacobian(F f, const Eigen::VectorXd& x, int rows) {
  const double h = 1e-6;
  Eigen::MatrixXd j(rows, x.size());
  for (int c = 0; c < x.size(); ++c) {
    Eigen::VectorXd a = x, b = x;
    a[c] += h;
    b[c] -= h;
    Eigen::VectorXd d = f(a) - f(b);
    if (rows >= 2) d[rows - 1] = math::wrapAngle(d[rows - 1]);  // last component is an angle
    j.col(c) = d / (2 * h);
  }
  return j;
}

/// f of a pose (or of a line) as a function of its vector, for numericJacobian.
template <typename F>
auto ofPose(F f) {
  return [f](const Eigen::VectorXd& v) {
    return Eigen::VectorXd(vec(f(math::SE2(v[0], v[1], v[2]))));
  };
}
template <typename F>
auto ofLine(F f) {
  return [f](const Eigen::VectorXd& v) { return Eigen::VectorXd(vec(f(Line{v[0], v[1]}))); };
}

/// An analytic Jacobian of f at x against central differences (relative 1e-6).
template <typename F, typename X>
testing::AssertionResult matchesCentralDifferences(const Eigen::MatrixXd& analytic, F f,
                                                   const X& x) {
  const Eigen::MatrixXd numeric = numericJacobian(f, vec(x), static_cast<int>(analytic.rows()));
  if (analytic.isApprox(numeric, 1e-6)) return testing::AssertionSuccess();
  return testing::AssertionFailure() << "analytic\n" << analytic << "\nnumeric\n" << numeric;
}

TEST(LineModel, PredictJacobiansMatchNumericalDifferentiation) {
  const math::SE2 p(1.0, -2.0, 0.7), d(0.3, -0.1, 0.2);
  Eigen::Matrix3d fx, fv;
  slam::predictPose(p, d, &fx, &fv);
  EXPECT_TRUE(matchesCentralDifferences(
      fx, ofPose([&](const math::SE2& q) { return slam::predictPose(q, d, nullptr, nullptr); }),
      p));
  EXPECT_TRUE(matchesCentralDifferences(
      fv, ofPose([&](const math::SE2& q) { return slam::predictPose(p, q, nullptr, nullptr); }),
      d));
}

// Both branches: the robot on the origin's side of the line, and beyond it (rho flips).
TEST(LineModel, ObservationJacobiansMatchNumericalDifferentiation) {
  for (const math::SE2& p : {math::SE2(0.5, 0.2, 0.3), math::SE2(4.0, 3.0, -2.0)}) {
    const Line l{2.0, 0.4};
    Eigen::Matrix<double, 2, 3> hr;
    Eigen::Matrix2d hl;
    slam::observeLine(p, l, &hr, &hl);
    EXPECT_TRUE(matchesCentralDifferences(
        hr, ofPose([&](const math::SE2& q) { return slam::observeLine(q, l, nullptr, nullptr); }),
        p));
    EXPECT_TRUE(matchesCentralDifferences(
        hl, ofLine([&](const Line& m) { return slam::observeLine(p, m, nullptr, nullptr); }), l));
  }
}

TEST(LineModel, InverseObservationRoundTripsAndItsJacobiansMatch) {
  for (const math::SE2& p : {math::SE2(0.5, 0.2, 0.3), math::SE2(-3.0, 1.0, 2.5)}) {
    for (const Line z : {Line{1.5, -0.8}, Line{0.7, 2.9}}) {
      Eigen::Matrix<double, 2, 3> gr;
      Eigen::Matrix2d gz;
      const Line m = slam::lineToMap(p, z, &gr, &gz);
      EXPECT_GE(m.rho_m, 0.0);
      const Line back = slam::observeLine(p, m, nullptr, nullptr);
      EXPECT_NEAR(back.rho_m, z.rho_m, 1e-12);
      EXPECT_NEAR(math::angleDiff(back.alpha_rad, z.alpha_rad), 0.0, 1e-12);
      EXPECT_TRUE(matchesCentralDifferences(
          gr, ofPose([&](const math::SE2& q) { return slam::lineToMap(q, z, nullptr, nullptr); }),
          p));
      EXPECT_TRUE(matchesCentralDifferences(
          gz, ofLine([&](const Line& o) { return slam::lineToMap(p, o, nullptr, nullptr); }), z));
    }
  }
}

slam::LineObservation obsOf(const Line& l, double sd_rho = 0.01, double sd_alpha = 0.005) {
  slam::LineObservation o;
  o.line = l;
  o.cov = Eigen::Vector2d(sd_rho * sd_rho, sd_alpha * sd_alpha).asDiagonal();
  o.start_m = Eigen::Vector2d(l.rho_m * std::cos(l.alpha_rad), l.rho_m * std::sin(l.alpha_rad));
  o.end_m = o.start_m + Eigen::Vector2d(-std::sin(l.alpha_rad), std::cos(l.alpha_rad));
  return o;
}

// The expanded Joseph form equals the textbook (I - K H) P on a well-conditioned case, computed by
// the independent math::KalmanFilter with the same linearisation.
TEST(LineEkfSlam, JosephUpdateEqualsTextbookUpdate) {
  slam::LineEkfSlamConfig cfg;
  cfg.confirm_sightings = 1;
  cfg.line_model_rho_std_m = cfg.line_model_alpha_std_rad = 0.0;  // the reference uses obs.cov
  slam::LineEkfSlam ekf(cfg, math::SE2(0, 0, 0), Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  ekf.update({obsOf(Line{2.0, 0.1}), obsOf(Line{1.5, 1.7})});
  ASSERT_EQ(ekf.numLandmarks(), 2);
  ekf.predict(math::SE2(0.2, 0.05, 0.1));
  const Eigen::VectorXd x0 = ekf.state();
  const Eigen::MatrixXd p0 = ekf.covariance();
  const std::vector<slam::LineObservation> obs{obsOf(Line{1.81, 0.0}), obsOf(Line{1.47, 1.61})};
  ASSERT_EQ(ekf.associate(obs), (std::vector<int>{0, 1}));
  // Reference: stacked H and innovation, z' = nu + H x so that z' - H x = nu.
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(4, x0.size()), r = Eigen::MatrixXd::Zero(4, 4);
  Eigen::VectorXd nu(4);
  const math::SE2 pose(x0[0], x0[1], x0[2]);
  for (int k = 0; k < 2; ++k) {
    Eigen::Matrix<double, 2, 3> hr;
    Eigen::Matrix2d hl;
    const Line pred = slam::observeLine(pose, ekf.landmark(k), &hr, &hl);
    nu.segment<2>(2 * k) = slam::lineInnovation(obs[k].line, pred);
    h.block<2, 3>(2 * k, 0) = hr;
    h.block<2, 2>(2 * k, slam::LineEkfSlam::landmarkIndex(k)) = hl;
    r.block<2, 2>(2 * k, 2 * k) = obs[k].cov;
  }
  math::KalmanFilter ref(x0, p0);
  ref.updateStandardForm(h, nu + h * x0, r);
  ekf.update(obs);
  EXPECT_TRUE(ekf.state().isApprox(ref.mean(), 1e-9));
  EXPECT_TRUE(ekf.covariance().isApprox(ref.cov(), 1e-9));
}

// Ill-conditioned: a nearly exact observation of a nearly unknown landmark. The covariance stays
// symmetric positive semi-definite.
TEST(LineEkfSlam, JosephUpdateStaysPositiveOnIllConditionedCase) {
  slam::LineEkfSlamConfig cfg;
  cfg.confirm_sightings = 1;
  slam::LineEkfSlam ekf(cfg, math::SE2(), Eigen::Vector3d(1e4, 1e4, 1.0).asDiagonal());
  ekf.update({obsOf(Line{3.0, 0.2}, 1e-6, 1e-7), obsOf(Line{2.0, 1.9}, 1e-6, 1e-7)});
  for (int i = 0; i < 20; ++i) {
    ekf.predict(math::SE2(0.0, 0.0, 0.0), Eigen::Vector3d(1e-12, 1e-12, 1e-12).asDiagonal());
    ekf.update({obsOf(Line{3.0, 0.2}, 1e-6, 1e-7), obsOf(Line{2.0, 1.9}, 1e-6, 1e-7)});
  }
  const Eigen::MatrixXd& p = ekf.covariance();
  EXPECT_TRUE(p.isApprox(p.transpose(), 1e-12));
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(p).eigenvalues();
  EXPECT_GT(ev.minCoeff(), -1e-9 * ev.maxCoeff()) << ev.transpose();
}

// Two parallel walls 0.3 m apart and a robot whose x is uncertain by 0.3 m: each observed line is
// individually compatible with both walls. Nearest neighbour pairs both with the nearer wall; JCBB
// finds the jointly compatible hypothesis (the robot moved 0.3 m).
TEST(LineEkfSlam, JcbbFindsTheHypothesisNearestNeighbourMisses) {
  slam::LineEkfSlamConfig cfg;
  cfg.confirm_sightings = 1;
  slam::LineEkfSlam ekf(cfg);
  ekf.update({obsOf(Line{2.0, 0.0}, 0.005, 0.002), obsOf(Line{2.3, 0.0}, 0.005, 0.002)});
  ASSERT_EQ(ekf.numLandmarks(), 2);
  ekf.predict(math::SE2(), Eigen::Vector3d(0.3 * 0.3, 1e-4, 1e-6).asDiagonal());
  const std::vector<slam::LineObservation> seen{obsOf(Line{1.7, 0.0}, 0.005, 0.002),
                                                obsOf(Line{2.0, 0.0}, 0.005, 0.002)};
  slam::LineEkfSlamConfig nn_cfg = cfg;
  nn_cfg.association.method = slam::Association::kNearestNeighbour;
  slam::LineEkfSlam nn(nn_cfg);
  nn.update({obsOf(Line{2.0, 0.0}, 0.005, 0.002), obsOf(Line{2.3, 0.0}, 0.005, 0.002)});
  nn.predict(math::SE2(), Eigen::Vector3d(0.3 * 0.3, 1e-4, 1e-6).asDiagonal());
  EXPECT_EQ(nn.associate(seen), (std::vector<int>{0, 0}));
  EXPECT_EQ(ekf.associate(seen), (std::vector<int>{0, 1}));
  ekf.update(seen);
  EXPECT_NEAR(ekf.pose().x_m, 0.3, 0.01);
}

TEST(LineEkfSlam, TentativeLandmarksAreDroppedConfirmedOnesKept) {
  slam::LineEkfSlamConfig cfg;
  cfg.confirm_sightings = 3;
  cfg.tentative_timeout_scans = 2;
  slam::LineEkfSlam ekf(cfg);
  ekf.update({obsOf(Line{2.0, 0.0}), obsOf(Line{1.0, 1.57})});
  ekf.update({obsOf(Line{2.0, 0.0})});
  ekf.update({obsOf(Line{2.0, 0.0})});  // wall 0 confirmed; wall 1 unseen for 2 scans: dropped
  ASSERT_EQ(ekf.numLandmarks(), 1);
  EXPECT_TRUE(ekf.landmarkInfo(0).confirmed());
  EXPECT_NEAR(ekf.landmark(0).rho_m, 2.0, 1e-6);
  EXPECT_EQ(ekf.state().size(), 5);
}

TEST(LineEkfSlam, BadConfigurationIsRejectedWithItsName) {
  slam::LineEkfSlamConfig cfg;
  cfg.association.gate_probability = 1.5;
  EXPECT_TRUE(test_support::refusedNaming([&] { slam::LineEkfSlam ekf(cfg); }, "gate_probability"));
  EXPECT_THROW(slam::parseAssociation("nearest"), std::invalid_argument);
}

}  // namespace

// Anchoring conditions the joint Gaussian: on the first landmark's estimate (two rows), then on
// the second reference's intersection with it along the first (one row, J = du/d(rho, alpha),
// here by central differences of the intersection computed from two lines). The remaining
// covariance is the Schur complement P_aa - P_ac C^T (C P_cc C^T)^-1 C P_ca computed directly
// from the un-anchored filter, and the mean is unchanged.
TEST(LineEkfSlam, AnchorConditionsTheStateOnTheAnchoredLandmarks) {
  slam::LineEkfSlamConfig cfg;
  cfg.confirm_sightings = 2;
  cfg.variant = slam::Variant::kAnchor;
  slam::LineEkfSlam ekf(cfg, math::SE2(), Eigen::Vector3d(0.04, 0.04, 0.01).asDiagonal());
  // Three walls: 0 and 1 parallel (x = 2, x = -1.5), 2 perpendicular (y = 1).
  const std::vector<slam::LineObservation> walls{obsOf(Line{2.0, 0.0}), obsOf(Line{1.5, M_PI}),
                                                 obsOf(Line{1.0, M_PI / 2})};
  ekf.update(walls);
  ekf.predict(math::SE2(0.1, 0.0, 0.0));
  const std::vector<slam::LineObservation> seen{obsOf(Line{1.9, 0.0}), obsOf(Line{1.6, M_PI}),
                                                obsOf(Line{1.0, M_PI / 2})};
  // The reference: the same update without anchoring, then conditioning by hand.
  slam::LineEkfSlamConfig plain_cfg = cfg;
  plain_cfg.variant = slam::Variant::kStandard;
  slam::LineEkfSlam plain(plain_cfg, math::SE2(), Eigen::Vector3d(0.04, 0.04, 0.01).asDiagonal());
  plain.update(walls);
  plain.predict(math::SE2(0.1, 0.0, 0.0));
  plain.update(seen);
  const auto res = ekf.update(seen);
  // Wall 0 is the anchor; wall 1 is parallel to it; wall 2 fixes the intersection.
  EXPECT_EQ(res.anchored, 2);
  ASSERT_EQ(ekf.numLandmarks(), 2);
  ASSERT_EQ(ekf.numFixedLandmarks(), 1);
  EXPECT_TRUE(ekf.fixedLandmark(0).anchor);
  EXPECT_NEAR(ekf.fixedLandmark(0).line.rho_m, plain.landmark(0).rho_m, 1e-12);
  EXPECT_FALSE(ekf.landmarkInfo(0).gauge);
  EXPECT_TRUE(ekf.landmarkInfo(1).gauge);
  // u(l2) = position along wall 0 (direction (-sin a0, cos a0) from its foot) where l2 crosses it.
  const Line a0 = plain.landmark(0);
  auto along = [&](const Line& l) {
    Eigen::Matrix2d n;
    n << std::cos(a0.alpha_rad), std::sin(a0.alpha_rad), std::cos(l.alpha_rad),
        std::sin(l.alpha_rad);
    const Eigen::Vector2d p = n.inverse() * Eigen::Vector2d(a0.rho_m, l.rho_m);
    return Eigen::Vector2d(-std::sin(a0.alpha_rad), std::cos(a0.alpha_rad))
        .dot(p - a0.rho_m * Eigen::Vector2d(std::cos(a0.alpha_rad), std::sin(a0.alpha_rad)));
  };
  const Line l2 = plain.landmark(2);
  const double h = 1e-6;
  const double du_drho =
      (along({l2.rho_m + h, l2.alpha_rad}) - along({l2.rho_m - h, l2.alpha_rad})) / (2 * h);
  const double du_dalpha =
      (along({l2.rho_m, l2.alpha_rad + h}) - along({l2.rho_m, l2.alpha_rad - h})) / (2 * h);
  const int n = static_cast<int>(plain.state().size());
  const int i0 = slam::LineEkfSlam::landmarkIndex(0), i2 = slam::LineEkfSlam::landmarkIndex(2);
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(3, n);
  c(0, i0) = 1.0;
  c(1, i0 + 1) = 1.0;
  c(2, i2) = du_drho;
  c(2, i2 + 1) = du_dalpha;
  const Eigen::MatrixXd& p = plain.covariance();
  const Eigen::MatrixXd cond = p - p * c.transpose() * (c * p * c.transpose()).inverse() * c * p;
  const std::vector<int> keep{
      0,  1,     2, slam::LineEkfSlam::landmarkIndex(1), slam::LineEkfSlam::landmarkIndex(1) + 1,
      i2, i2 + 1};
  Eigen::MatrixXd expected(7, 7);
  for (int a = 0; a < 7; ++a)
    for (int b = 0; b < 7; ++b) expected(a, b) = cond(keep[a], keep[b]);
  EXPECT_TRUE(ekf.covariance().isApprox(expected, 1e-6)) << ekf.covariance() << "\n---\n"
                                                         << expected;
  for (int a = 0; a < 7; ++a) EXPECT_NEAR(ekf.state()[a], plain.state()[keep[a]], 1e-12);
  // The frame is fixed: seeing the references again shrinks the pose covariance in every
  // direction; the anchored line's index continues after the state landmarks.
  ekf.predict(math::SE2(0.0, 0.0, 0.0), Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  const Eigen::Matrix3d before = ekf.poseCovariance();
  const std::vector<slam::LineObservation> refs_only{obsOf(Line{1.9, 0.0}),
                                                     obsOf(Line{1.0, M_PI / 2})};
  EXPECT_EQ(ekf.associate(refs_only), (std::vector<int>{2, 1}));
  ekf.update(refs_only);
  EXPECT_LT(ekf.poseCovariance()(0, 0), 0.5 * before(0, 0));
  EXPECT_LT(ekf.poseCovariance()(1, 1), 0.5 * before(1, 1));
  EXPECT_LT(ekf.poseCovariance()(2, 2), 0.5 * before(2, 2));
}

// A retired landmark leaves the state with its marginal covariance and still corrects the pose:
// the update then equals a Kalman update on the pose with R + H_l Sigma H_l^T.
TEST(LineEkfSlam, RetiredLandmarksLeaveTheStateAndStillCorrectThePose) {
  slam::LineEkfSlamConfig cfg;
  cfg.confirm_sightings = 1;
  cfg.retire_after_updates = 2;
  cfg.line_model_rho_std_m = cfg.line_model_alpha_std_rad = 0.0;  // the reference uses obs.cov
  slam::LineEkfSlam ekf(cfg, math::SE2(), Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  for (int i = 0; i < 3; ++i) ekf.update({obsOf(Line{2.0, 0.1})});
  ASSERT_EQ(ekf.numLandmarks(), 0);
  ASSERT_EQ(ekf.numFixedLandmarks(), 1);
  const slam::FixedLandmark f = ekf.fixedLandmark(0);
  EXPECT_FALSE(f.anchor);
  EXPECT_GT(f.cov.determinant(), 0.0);
  ekf.predict(math::SE2(0.1, 0.0, 0.0));
  const Eigen::Vector3d x0 = ekf.state();
  const Eigen::Matrix3d p0 = ekf.covariance();
  const slam::LineObservation o = obsOf(Line{1.85, 0.1});
  Eigen::Matrix<double, 2, 3> hr;
  Eigen::Matrix2d hl;
  const Line pred = slam::observeLine(ekf.pose(), f.line, &hr, &hl);
  math::KalmanFilter ref(x0, p0);
  ref.update(hr, slam::lineInnovation(o.line, pred) + hr * x0, o.cov + hl * f.cov * hl.transpose());
  ASSERT_EQ(ekf.associate({o}), (std::vector<int>{0}));
  ekf.update({o});
  EXPECT_TRUE(ekf.state().isApprox(ref.mean(), 1e-9));
  EXPECT_TRUE(ekf.covariance().isApprox(ref.cov(), 1e-9));
  EXPECT_EQ(ekf.fixedLandmark(0).info.sightings, 4);
}

// The external sensor (eqs. 26-27) is a Kalman update with H = [I 0]: compare with
// math::KalmanFilter, landmarks included through their cross-covariance.
TEST(LineEkfSlam, ExternalPositionUpdateEqualsKalmanUpdateWithIdentityRows) {
  slam::LineEkfSlamConfig cfg;
  cfg.confirm_sightings = 1;
  cfg.variant = slam::Variant::kExternal;
  slam::LineEkfSlam ekf(cfg, math::SE2(), Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  ekf.update({obsOf(Line{2.0, 0.1})});
  ekf.predict(math::SE2(0.3, 0.1, 0.05));
  const Eigen::VectorXd x0 = ekf.state();
  const Eigen::MatrixXd p0 = ekf.covariance();
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, x0.size());
  h(0, 0) = h(1, 1) = 1.0;
  const Eigen::Vector2d z(0.35, 0.05);
  const Eigen::Matrix2d r = Eigen::Vector2d(0.0025, 0.0025).asDiagonal();
  math::KalmanFilter ref(x0, p0);
  ref.update(h, z, r);
  ekf.updateExternalPosition(z, r);
  EXPECT_TRUE(ekf.state().isApprox(ref.mean(), 1e-9));
  EXPECT_TRUE(ekf.covariance().isApprox(ref.cov(), 1e-9));
  EXPECT_THROW(slam::parseVariant("anchored"), std::invalid_argument);
  EXPECT_EQ(slam::variantName(slam::parseVariant("external")), "external");
}

// transformBetweenLinePairs inverts lineToMap for two non-parallel lines, including lines whose
// representation flips to keep rho >= 0; lineThrough agrees with the Hessian form.
TEST(LineModel, TransformBetweenLinePairsRecoversTheFrame) {
  const math::SE2 t(1.3, -2.1, 2.5);
  const Line from[2] = {slam::lineThrough({0.0, 1.0}, {4.0, 1.0}),
                        slam::lineThrough({0.5, -3.0}, {0.5, 3.0})};
  EXPECT_NEAR(from[0].rho_m, 1.0, 1e-12);
  EXPECT_NEAR(from[0].alpha_rad, M_PI / 2, 1e-12);
  const Line to[2] = {slam::lineToMap(t, from[0], nullptr, nullptr),
                      slam::lineToMap(t, from[1], nullptr, nullptr)};
  math::SE2 got;
  ASSERT_TRUE(slam::transformBetweenLinePairs(from, to, &got, t.yaw_rad + 0.4));
  EXPECT_NEAR(got.x_m, t.x_m, 1e-9);
  EXPECT_NEAR(got.y_m, t.y_m, 1e-9);
  EXPECT_NEAR(math::angleDiff(got.yaw_rad, t.yaw_rad), 0.0, 1e-9);
  const Line parallel[2] = {from[0], slam::lineThrough({0.0, 2.0}, {4.0, 2.0})};
  EXPECT_FALSE(slam::transformBetweenLinePairs(parallel, parallel, &got));
}

// The map YAML round-trips through yaml-cpp with the state's numbers, and a failed write leaves
// the existing file untouched.
TEST(LineMapYaml, WritesLandmarksAndCovarianceAtomically) {
  slam::LineEkfSlamConfig cfg;
  cfg.confirm_sightings = 1;
  slam::LineEkfSlam ekf(cfg, math::SE2(), Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  ekf.update({obsOf(Line{2.0, 0.1}), obsOf(Line{1.5, 1.7})});
  const std::string path = testing::TempDir() + "/line_map_test.yaml";
  slam::writeLineMapYaml(path, ekf);
  const YAML::Node y = YAML::LoadFile(path);
  ASSERT_EQ(y["landmarks"].size(), 2u);
  EXPECT_NEAR(y["landmarks"][1]["rho_m"].as<double>(), ekf.landmark(1).rho_m, 1e-12);
  EXPECT_EQ(y["state_covariance"]["dim"].as<int>(), 7);
  ASSERT_EQ(y["state_covariance"]["data"].size(), 49u);
  for (int r = 0; r < 7; ++r)  // shortest round-trip text: every value reads back exactly
    for (int c = 0; c < 7; ++c)
      EXPECT_EQ(y["state_covariance"]["data"][7 * r + c].as<double>(), ekf.covariance()(r, c));
  EXPECT_THROW(slam::writeLineMapYaml("/nonexistent_dir/map.yaml", ekf), std::runtime_error);
  std::remove(path.c_str());
}

// The standard model cannot observe the map's global heading: lines only tell where the robot is
// relative to lines it placed itself. So from a start pose with yaw variance s2, no sequence of
// moves and line observations may bring the robot's yaw variance below s2 (Huang, Mourikis &
// Roumeliotis 2008). The plain EKF, linearised at ever-changing estimates, does (spurious
// information; the cause of its over-confident NEES on long loops); the first-estimates Jacobians
// keep the bound. Noisy odometry and observations of a square room while driving a circle.
TEST(LineEkfSlam, FirstEstimatesJacobiansKeepTheHeadingUnobservable) {
  const std::vector<Line> room{Line{3.0, 0.0}, Line{3.0, M_PI / 2}, Line{3.0, M_PI},
                               Line{3.0, -M_PI / 2}};
  auto run = [&](bool fej) {
    slam::LineEkfSlamConfig cfg;
    cfg.first_estimate_jacobians = fej;
    cfg.confirm_sightings = 1;
    cfg.merge_landmarks = false;
    const double yaw_var0 = 0.05;
    slam::LineEkfSlam ekf(cfg, math::SE2(), Eigen::Vector3d(1e-4, 1e-4, yaw_var0).asDiagonal());
    math::Rng rng(7);
    math::SE2 truth;
    double min_ratio = 1.0;
    for (int k = 0; k < 300; ++k) {
      if (k > 0) {
        const math::SE2 d(0.1, 0.0, 0.1);  // a circle of radius 1 m
        truth = truth * d;
        const Eigen::Matrix3d q = Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal();
        ekf.predict(math::SE2{d.x_m + rng.gaussian(0, 0.01), d.y_m + rng.gaussian(0, 0.01),
                              d.yaw_rad + rng.gaussian(0, 0.01)},
                    q);
      }
      std::vector<slam::LineObservation> obs;
      for (const Line& l : room) {
        Line z = slam::observeLine(truth, l, nullptr, nullptr);
        z.rho_m += rng.gaussian(0, 0.02);
        z.alpha_rad += rng.gaussian(0, 0.01);
        obs.push_back(obsOf(z, 0.02, 0.01));
      }
      ekf.update(obs);
      min_ratio = std::min(min_ratio, ekf.poseCovariance()(2, 2) / yaw_var0);
    }
    EXPECT_EQ(ekf.numLandmarks(), 4);
    return min_ratio;
  };
  const double plain = run(false), fej = run(true);
  EXPECT_LT(plain, 0.9) << "the plain EKF should show the spurious heading information";
  EXPECT_GT(fej, 0.999);
}

// A wall broken by an alcove is one line seen as two segments in one scan. With share_landmarks,
// JCBB pairs both with the one landmark (two independent measurements of it) and starts nothing
// new; without it, the second piece must start a landmark of its own.
TEST(LineEkfSlam, PiecesOfOneWallInOneScanShareTheLandmark) {
  for (const bool share : {true, false}) {
    slam::LineEkfSlamConfig cfg;
    cfg.confirm_sightings = 1;
    cfg.association.share_landmarks = share;
    slam::LineEkfSlam ekf(cfg);
    ekf.update({obsOf(Line{2.0, 0.3})});
    ASSERT_EQ(ekf.numLandmarks(), 1);
    ekf.predict(math::SE2(0.05, 0.0, 0.0));
    const Line seen = slam::observeLine(ekf.pose(), Line{2.0, 0.3}, nullptr, nullptr);
    slam::LineObservation a = obsOf(seen), b = obsOf(Line{seen.rho_m + 0.004, seen.alpha_rad});
    b.start_m = a.end_m + Eigen::Vector2d(-std::sin(seen.alpha_rad), std::cos(seen.alpha_rad));
    b.end_m = b.start_m + Eigen::Vector2d(-std::sin(seen.alpha_rad), std::cos(seen.alpha_rad));
    const slam::LineEkfSlam::UpdateResult res = ekf.update({a, b});
    if (share) {
      EXPECT_EQ(res.association, (std::vector<int>{0, 0}));
      EXPECT_EQ(res.added, 0);
      EXPECT_EQ(res.nis_dof, 4);
      EXPECT_EQ(ekf.numLandmarks(), 1);
      EXPECT_EQ(ekf.landmarkInfo(0).sightings, 2);  // one per scan, however many pieces
    } else {
      EXPECT_EQ(res.association[0] + res.association[1], -1);  // one paired, one new
      EXPECT_EQ(res.added, 1);
    }
  }
}

namespace {
// Three walls of a room in map: x = 3, y = 2, x = -4.
const Line kWalls[3] = {Line{3.0, 0.0}, Line{2.0, M_PI / 2}, Line{4.0, M_PI}};
std::vector<slam::LineObservation> wallsSeenFrom(const math::SE2& pose) {
  std::vector<slam::LineObservation> out;
  for (const Line& w : kWalls) out.push_back(obsOf(slam::observeLine(pose, w, nullptr, nullptr)));
  return out;
}
}  // namespace

// A map saved by ~save_map reads back as the same lines with their marginal covariances, and a
// filter given them (extend_map off) localizes from a wrong start without starting landmarks.
TEST(LineMapYaml, ReadsBackTheMapAndLocalizesAgainstIt) {
  slam::LineEkfSlamConfig cfg;
  cfg.confirm_sightings = 1;
  slam::LineEkfSlam mapper(cfg, math::SE2(), Eigen::Vector3d(1e-6, 1e-6, 1e-6).asDiagonal());
  for (int k = 0; k < 3; ++k) {
    mapper.predict(math::SE2());
    mapper.update(wallsSeenFrom(math::SE2()));
  }
  ASSERT_EQ(mapper.numLandmarks(), 3);
  const std::string path = testing::TempDir() + "/line_map_read_test.yaml";
  slam::writeLineMapYaml(path, mapper);
  const std::vector<slam::FixedLandmark> map = slam::readLineMapYaml(path);
  ASSERT_EQ(map.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(map[i].line.rho_m, mapper.landmark(i).rho_m);
    EXPECT_EQ(map[i].line.alpha_rad, mapper.landmark(i).alpha_rad);
    EXPECT_TRUE(map[i].cov.isApprox(mapper.landmarkCovariance(i), 1e-12));
    EXPECT_EQ(map[i].info.id, mapper.landmarkInfo(i).id);
  }
  std::remove(path.c_str());

  slam::LineEkfSlamConfig loc_cfg;
  loc_cfg.extend_map = false;
  const math::SE2 truth(0.3, -0.2, 0.1);
  slam::LineEkfSlam loc(loc_cfg, math::SE2(0.5, -0.35, 0.15),
                        Eigen::Vector3d(0.04, 0.04, 0.01).asDiagonal());
  loc.addFixedLandmarks(map);
  std::vector<slam::LineObservation> obs = wallsSeenFrom(truth);
  obs.push_back(obsOf(Line{1.0, -M_PI / 2}));  // a wall the map does not have (y = -1.2)
  for (int k = 0; k < 5; ++k) {
    loc.predict(math::SE2());
    loc.update(obs);
  }
  EXPECT_NEAR(loc.pose().x_m, truth.x_m, 0.02);
  EXPECT_NEAR(loc.pose().y_m, truth.y_m, 0.02);
  EXPECT_NEAR(math::angleDiff(loc.pose().yaw_rad, truth.yaw_rad), 0.0, 0.01);
  EXPECT_EQ(loc.numLandmarks(), 0);  // nothing started: the map is not extended
  EXPECT_EQ(loc.numFixedLandmarks(), 3);
}

// A malformed map names the file and the line; a covariance of the wrong size is refused.
TEST(LineMapYaml, RefusesAMalformedMapNamingFileAndLine) {
  const std::string path = testing::TempDir() + "/line_map_bad_test.yaml";
  auto expectError = [&](const std::string& text, const std::string& needle) {
    {
      std::ofstream f(path);
      f << text;
    }
    try {
      slam::readLineMapYaml(path);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expectError(
      "landmarks:\n  - {id: 1, alpha_rad: 0.1, confirmed: true}\n"
      "state_covariance: {dim: 5, data: [1,0,0,0,0, 0,1,0,0,0, 0,0,1,0,0, 0,0,0,1,0, 0,0,0,0,1]}\n",
      ":2: missing 'rho_m'");
  expectError("landmarks: []\nstate_covariance: {dim: 5, data: [1, 0, 0, 1]}\n", "does not match");
  expectError("landmarks: [\n", "");
  expectError(
      "landmarks:\n  - {id: 1, rho_m: 2, alpha_rad: 0.1}\n"
      "state_covariance: {dim: 5, data: [1,0,0,0,0, 0,1,0,0,0, 0,0,1,0,0, 0,0,0,1,2, 0,0,0,2,1]}\n",
      "positive semi-definite");
  std::remove(path.c_str());
  EXPECT_THROW(slam::readLineMapYaml("/nonexistent_dir/map.yaml"), std::runtime_error);
}
