// LineEkfSlam's data association (line_ekf_slam.h): each observation's individually compatible
// landmarks, then joint compatibility branch and bound (Neira and Tardos 2001) over them, or the
// nearest neighbour. The filter's model and updates are in line_ekf_slam.cpp.
#include <Eigen/Cholesky>
#include <algorithm>
#include <limits>
#include <vector>

#include "adaptive_perception/math/chi_square.h"
#include "adaptive_perception/slam/line_ekf_slam.h"

namespace adaptive_perception::slam {

double LineEkfSlam::individualMahalanobis(const LineObservation& obs, int lm) const {
  // jointMahalanobis of the single pairing, in fixed-size arithmetic (no allocation): this runs for
  // every observation against every landmark.
  Eigen::Matrix<double, 2, 3> hr;
  Eigen::Matrix2d hl, s;
  const Eigen::Vector2d nu = linearise(obs, lm, &hr, &hl, &s);
  s += hr * p_.topLeftCorner<3, 3>() * hr.transpose();
  if (lm < numLandmarks()) {
    const int c = landmarkIndex(lm);
    const Eigen::Matrix2d x = hr * p_.block<3, 2>(0, c) * hl.transpose();
    s += x + x.transpose() + hl * p_.block<2, 2>(c, c) * hl.transpose();
  }
  const Eigen::LDLT<Eigen::Matrix2d> ldlt(s);
  return nu.dot(ldlt.solve(nu));
}

double LineEkfSlam::gate(int dof) const {
  if (static_cast<int>(gate_by_dof_.size()) <= dof) {
    const size_t from = gate_by_dof_.size();
    gate_by_dof_.resize(dof + 1);
    for (size_t k = std::max<size_t>(from, 1); k < gate_by_dof_.size(); ++k)
      gate_by_dof_[k] = math::chiSquareQuantile(config_.gate_probability, static_cast<int>(k));
  }
  return gate_by_dof_[dof];
}

struct LineEkfSlam::JcbbBranch {
  struct Pair {
    Pairing pairing;
    Eigen::Vector2d nu;
    Eigen::Matrix<double, 2, 3> hr;
    Eigen::Matrix2d hl, r;
    int col = -1;  // the landmark's state index; -1 for a fixed landmark
  };
  std::vector<Pair> pairs;
  std::vector<double> d2;  // joint Mahalanobis distance with the first k + 1 pairings
  Eigen::MatrixXd l;       // lower factor of S, 2 rows per pairing
  Eigen::VectorXd w;       // L^-1 nu
  std::vector<Pairing> pairings() const {
    std::vector<Pairing> out;
    for (const Pair& p : pairs) out.push_back(p.pairing);
    return out;
  }
  double distance() const { return d2.empty() ? 0.0 : d2.back(); }
};

void LineEkfSlam::jcbb(const std::vector<LineObservation>& obs,
                       const std::vector<std::vector<int>>& candidates, size_t i,
                       JcbbBranch& branch, std::vector<Pairing>& best, double& best_d2,
                       long& nodes) const {
  ++nodes;
  const size_t depth = branch.pairs.size();
  if (i == obs.size()) {
    const double d2 = branch.distance();
    if (depth > best.size() || (depth == best.size() && d2 < best_d2)) {
      best = branch.pairings();
      best_d2 = d2;
    }
    return;
  }
  // Bound: even pairing every remaining observation cannot beat the best.
  if (depth + (obs.size() - i) < best.size()) return;
  // Budget: JCBB is exponential in the worst case (many parallel walls); past the budget the best
  // hypothesis found so far stands.
  if (nodes > config_.jcbb_max_nodes) return;
  const Eigen::Matrix3d prr = p_.topLeftCorner<3, 3>();
  for (int lm : candidates[i]) {
    bool used = false;
    if (!config_.share_landmarks)
      for (const auto& p : branch.pairs) used |= p.pairing.lm == lm;
    if (used) continue;
    JcbbBranch::Pair q;
    q.pairing = {static_cast<int>(i), lm};
    q.nu = linearise(obs[i], lm, &q.hr, &q.hl, &q.r);
    if (lm < numLandmarks()) q.col = landmarkIndex(lm);
    // The new pairing's covariance with each on the branch (the 2 x 2 blocks of H P H^T) and its
    // own.
    const auto cross = [&](const JcbbBranch::Pair& a, const JcbbBranch::Pair& c) {
      Eigen::Matrix2d sac = a.hr * prr * c.hr.transpose();
      if (c.col >= 0) sac += a.hr * p_.block<3, 2>(0, c.col) * c.hl.transpose();
      if (a.col >= 0) {
        sac += a.hl * p_.block<2, 3>(a.col, 0) * c.hr.transpose();
        if (c.col >= 0) sac += a.hl * p_.block<2, 2>(a.col, c.col) * c.hl.transpose();
      }
      return sac;
    };
    const int m2 = 2 * static_cast<int>(depth);
    Eigen::MatrixXd c(m2, 2);
    for (size_t k = 0; k < depth; ++k) c.middleRows<2>(2 * k) = cross(branch.pairs[k], q);
    const Eigen::Matrix2d dqq = cross(q, q) + q.r;
    // Extend the factor: [L 0; B^T E] with B = L^-1 C and E E^T = D - B^T B.
    Eigen::MatrixXd bt(2, m2);
    Eigen::Matrix2d schur = dqq;
    Eigen::Vector2d rhs = q.nu;
    if (depth > 0) {
      const Eigen::MatrixXd bmat =
          branch.l.topLeftCorner(m2, m2).triangularView<Eigen::Lower>().solve(c);
      bt = bmat.transpose();
      schur -= bt * bmat;
      rhs -= bt * branch.w.head(m2);
    }
    const Eigen::LLT<Eigen::Matrix2d> e(schur);
    if (e.info() != Eigen::Success) continue;  // not positive definite: not jointly compatible
    const Eigen::Vector2d wq = e.matrixL().solve(rhs);
    const double d2 = branch.distance() + wq.squaredNorm();
    const int dof = m2 + 2;
    if (d2 > gate(dof)) continue;
    if (branch.l.rows() < dof) {
      const int rows = std::max<int>(dof, 2 * static_cast<int>(obs.size()));
      branch.l.conservativeResize(rows, rows);
      branch.w.conservativeResize(rows);
    }
    if (depth > 0) branch.l.block(m2, 0, 2, m2) = bt;
    branch.l.block<2, 2>(m2, m2) = e.matrixL();
    branch.w.segment<2>(m2) = wq;
    branch.pairs.push_back(q);
    branch.d2.push_back(d2);
    jcbb(obs, candidates, i + 1, branch, best, best_d2, nodes);
    branch.pairs.pop_back();
    branch.d2.pop_back();
  }
  // The null hypothesis for observation i (new or spurious line).
  if (depth + (obs.size() - i - 1) >= best.size())
    jcbb(obs, candidates, i + 1, branch, best, best_d2, nodes);
}

std::vector<int> LineEkfSlam::associate(const std::vector<LineObservation>& obs) const {
  const double gate2 = gate(2);
  std::vector<std::vector<int>> candidates(obs.size());
  std::vector<std::vector<double>> d2s(obs.size());
  for (size_t i = 0; i < obs.size(); ++i) {
    for (int j = 0; j < numLandmarks() + numFixedLandmarks(); ++j) {
      const double d2 = individualMahalanobis(obs[i], j);
      if (d2 <= gate2) {
        candidates[i].push_back(j);
        d2s[i].push_back(d2);
      }
    }
    // Most compatible first: JCBB then finds good hypotheses early and prunes more.
    std::vector<size_t> order(candidates[i].size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return d2s[i][a] < d2s[i][b]; });
    std::vector<int> c;
    std::vector<double> d;
    for (size_t k : order) {
      c.push_back(candidates[i][k]);
      d.push_back(d2s[i][k]);
    }
    candidates[i] = c;
    d2s[i] = d;
  }
  std::vector<int> out(obs.size(), -1);
  if (config_.association == Association::kNearestNeighbour) {
    for (size_t i = 0; i < obs.size(); ++i)
      if (!candidates[i].empty()) out[i] = candidates[i].front();
    return out;
  }
  JcbbBranch branch;
  std::vector<Pairing> best;
  double best_d2 = std::numeric_limits<double>::infinity();
  long nodes = 0;
  jcbb(obs, candidates, 0, branch, best, best_d2, nodes);
  for (const auto& p : best) out[p.obs] = p.lm;
  return out;
}

}  // namespace adaptive_perception::slam
