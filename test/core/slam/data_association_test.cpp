// Data association: the individual distance against the stacked H P H^T + R written out in full,
// and nearest neighbour and JCBB against a brute-force search over every assignment, each judged
// with the full stacked innovation covariance inverted from scratch.
#include "adaptive_perception/slam/data_association.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "../refusal.h"
#include "adaptive_perception/math/chi_square.h"
#include "adaptive_perception/math/rng.h"

using namespace adaptive_perception;
using slam::LinearPairing;

namespace {

// A random problem: a state of the pose and `landmarks` (2 rows each) plus `fixed` landmarks
// outside it, `observations` observations, and for each pairing a random linearisation.
struct Problem {
  Eigen::MatrixXd p;
  std::vector<std::vector<LinearPairing>> q;  // [obs][lm]
  int observations = 0, landmarks = 0;
};

Problem randomProblem(math::Rng& rng, int observations, int landmarks, int fixed) {
  Problem pr;
  pr.observations = observations;
  pr.landmarks = landmarks + fixed;
  const int n = 3 + 2 * landmarks;
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = rng.gaussian(0, 0.1);
  pr.p = a * a.transpose() + 0.01 * Eigen::MatrixXd::Identity(n, n);
  pr.q.resize(observations);
  for (int i = 0; i < observations; ++i) {
    for (int lm = 0; lm < pr.landmarks; ++lm) {
      LinearPairing q;
      for (int r = 0; r < 2; ++r) {
        for (int c = 0; c < 3; ++c) q.hr(r, c) = rng.gaussian(0, 1);
        for (int c = 0; c < 2; ++c) q.hl(r, c) = rng.gaussian(0, 1);
      }
      const double sd = rng.uniform(0.02, 0.1);
      q.r = Eigen::Matrix2d::Identity() * sd * sd;
      q.col = lm < landmarks ? 3 + 2 * lm : -1;
      // The innovation: `scale` standard deviations of its own covariance S = H P H^T + R, so
      // that about a third of the pairings pass the 99 % gate.
      const Eigen::MatrixXd h = [&] {
        Eigen::MatrixXd m = Eigen::MatrixXd::Zero(2, n);
        m.leftCols<3>() = q.hr;
        if (q.col >= 0) m.block<2, 2>(0, q.col) = q.hl;
        return m;
      }();
      const Eigen::Matrix2d s = h * pr.p * h.transpose() + q.r;
      const double scale = rng.uniform(0.0, 6.0);
      q.nu = s.llt().matrixL() * Eigen::Vector2d{rng.gaussian(0, 1), rng.gaussian(0, 1)} * scale;
      pr.q[i].push_back(q);
    }
  }
  return pr;
}

// The full 2 x n measurement Jacobian of one pairing.
Eigen::MatrixXd fullH(const LinearPairing& q, int n) {
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, n);
  h.leftCols<3>() = q.hr;
  if (q.col >= 0) h.block<2, 2>(0, q.col) = q.hl;
  return h;
}

// nu^T S^-1 nu of a set of pairings stacked, S = H P H^T + blockdiag(R), by a dense inverse.
double jointDistance(const std::vector<const LinearPairing*>& set, const Eigen::MatrixXd& p) {
  const int m = static_cast<int>(set.size()), n = static_cast<int>(p.rows());
  if (m == 0) return 0.0;
  Eigen::MatrixXd h(2 * m, n);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  Eigen::VectorXd nu(2 * m);
  for (int k = 0; k < m; ++k) {
    h.middleRows(2 * k, 2) = fullH(*set[k], n);
    r.block(2 * k, 2 * k, 2, 2) = set[k]->r;
    nu.segment<2>(2 * k) = set[k]->nu;
  }
  const Eigen::MatrixXd s = h * p * h.transpose() + r;
  return nu.dot(s.inverse() * nu);
}

// Every assignment (each observation to -1 or a landmark) whose pairings are each individually
// compatible and whose every prefix in observation order is jointly compatible; the one with the
// most pairings, then the smallest joint distance.
std::vector<int> bruteForceJcbb(const Problem& pr, double gate_probability, bool share) {
  std::vector<int> best(pr.observations, -1), current(pr.observations, -1);
  int best_count = 0;
  double best_d2 = 0.0;
  const std::function<void(int)> visit = [&](int i) {
    if (i == pr.observations) {
      std::vector<const LinearPairing*> set;
      for (int k = 0; k < pr.observations; ++k) {
        if (current[k] < 0) continue;
        set.push_back(&pr.q[k][current[k]]);
        const std::vector<const LinearPairing*> one{set.back()};
        if (jointDistance(one, pr.p) > math::chiSquareQuantile(gate_probability, 2)) return;
        const int dof = 2 * static_cast<int>(set.size());
        if (jointDistance(set, pr.p) > math::chiSquareQuantile(gate_probability, dof)) return;
      }
      const int count = static_cast<int>(set.size());
      const double d2 = jointDistance(set, pr.p);
      if (count > best_count || (count == best_count && d2 < best_d2)) {
        best = current;
        best_count = count;
        best_d2 = d2;
      }
      return;
    }
    for (int lm = -1; lm < pr.landmarks; ++lm) {
      bool used = false;
      for (int k = 0; k < i && !share; ++k) used |= lm >= 0 && current[k] == lm;
      if (used) continue;
      current[i] = lm;
      visit(i + 1);
    }
    current[i] = -1;
  };
  visit(0);
  return best;
}

}  // namespace

TEST(DataAssociation, IndividualDistanceIsTheFullStackedForm) {
  math::Rng rng(1);
  for (int trial = 0; trial < 50; ++trial) {
    const Problem pr = randomProblem(rng, 1, 3, 1);
    for (int lm = 0; lm < pr.landmarks; ++lm) {
      const LinearPairing& q = pr.q[0][lm];
      const std::vector<const LinearPairing*> one{&q};
      EXPECT_NEAR(slam::DataAssociation::mahalanobis(q, pr.p), jointDistance(one, pr.p),
                  1e-9 * (1.0 + jointDistance(one, pr.p)));
    }
  }
}

TEST(DataAssociation, GateIsTheChiSquareQuantile) {
  slam::DataAssociationConfig c;
  c.gate_probability = 0.95;
  const slam::DataAssociation da(c);
  EXPECT_NEAR(da.gate(2), 5.991, 1e-3);  // chi-square tables: 95 % at 2 dof
  EXPECT_NEAR(da.gate(4), 9.488, 1e-3);  // and at 4 dof
}

TEST(DataAssociation, NearestNeighbourPicksTheClosestCompatibleLandmark) {
  math::Rng rng(2);
  slam::DataAssociationConfig c;
  c.method = slam::Association::kNearestNeighbour;
  const slam::DataAssociation da(c);
  int paired = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Problem pr = randomProblem(rng, 3, 3, 1);
    const std::vector<int> got = da.associate(pr.observations, pr.landmarks, pr.p,
                                              [&](int i, int lm) { return pr.q[i][lm]; });
    for (int i = 0; i < pr.observations; ++i) {
      int want = -1;
      double want_d2 = da.gate(2);
      for (int lm = 0; lm < pr.landmarks; ++lm) {
        const std::vector<const LinearPairing*> one{&pr.q[i][lm]};
        const double d2 = jointDistance(one, pr.p);
        if (d2 <= want_d2) {
          want = lm;
          want_d2 = d2;
        }
      }
      EXPECT_EQ(got[i], want) << "trial " << trial << " observation " << i;
      paired += want >= 0;
    }
  }
  EXPECT_GT(paired, 20);      // the problems pair some observations and leave others
  EXPECT_LT(paired, 40 * 3);  // not every one of the 40 x 3 observations
}

TEST(DataAssociation, JcbbFindsTheLargestJointlyCompatibleSetAsBruteForceDoes) {
  for (const bool share : {true, false}) {
    math::Rng rng(share ? 3 : 4);
    slam::DataAssociationConfig c;
    c.share_landmarks = share;
    const slam::DataAssociation da(c);
    int pairings = 0, null_pairings = 0;
    for (int trial = 0; trial < 60; ++trial) {
      const Problem pr = randomProblem(rng, 4, 3, 1);
      const std::vector<int> want = bruteForceJcbb(pr, c.gate_probability, share);
      const std::vector<int> got = da.associate(pr.observations, pr.landmarks, pr.p,
                                                [&](int i, int lm) { return pr.q[i][lm]; });
      EXPECT_EQ(got, want) << "trial " << trial << (share ? " shared" : " one-to-one");
      for (int lm : want) (lm >= 0 ? pairings : null_pairings) += 1;
    }
    EXPECT_GT(pairings, 40);  // the cases are neither all paired nor all new
    EXPECT_GT(null_pairings, 20);
  }
}

TEST(DataAssociation, RefusesABadConfigNamingTheField) {
  slam::DataAssociationConfig c;
  c.gate_probability = 1.5;
  EXPECT_TRUE(
      test_support::refusedNaming([&] { slam::DataAssociation da(c); }, "gate_probability"));
  c = {};
  c.jcbb_max_nodes = 0;
  EXPECT_THROW(slam::DataAssociation{c}, std::invalid_argument);
  EXPECT_EQ(slam::parseAssociation(slam::associationName(slam::Association::kJcbb)),
            slam::Association::kJcbb);
  EXPECT_THROW(slam::parseAssociation("nearest"), std::invalid_argument);
}
