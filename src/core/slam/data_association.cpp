#include "adaptive_perception/slam/data_association.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/math/chi_square.h"

namespace adaptive_perception::slam {

const config::EnumNames<Association>& associations() {
  static const config::EnumNames<Association> names(
      "association", {{Association::kNearestNeighbour, "nn"}, {Association::kJcbb, "jcbb"}});
  return names;
}

Association parseAssociation(const std::string& name) { return associations().parse(name); }
std::string associationName(Association a) { return associations().name(a); }

void DataAssociationConfig::validate() const {
  fields().validate(*this);
  if (jcbb_max_nodes < 1)
    throw std::invalid_argument("jcbb_max_nodes = " + std::to_string(jcbb_max_nodes) +
                                " (allowed: >= 1)");
}

DataAssociation::DataAssociation(DataAssociationConfig config) : config_(std::move(config)) {
  config_.validate();
}

double DataAssociation::mahalanobis(const LinearPairing& q, const Eigen::MatrixXd& p) {
  // Fixed-size arithmetic (no allocation): this runs for every observation against every
  // landmark.
  Eigen::Matrix2d s = q.r + q.hr * p.topLeftCorner<3, 3>() * q.hr.transpose();
  if (q.col >= 0) {
    const Eigen::Matrix2d x = q.hr * p.block<3, 2>(0, q.col) * q.hl.transpose();
    s += x + x.transpose() + q.hl * p.block<2, 2>(q.col, q.col) * q.hl.transpose();
  }
  const Eigen::LDLT<Eigen::Matrix2d> ldlt(s);
  return q.nu.dot(ldlt.solve(q.nu));
}

double DataAssociation::gate(int dof) const {
  if (static_cast<int>(gate_by_dof_.size()) <= dof) {
    const size_t from = gate_by_dof_.size();
    gate_by_dof_.resize(dof + 1);
    for (size_t k = std::max<size_t>(from, 1); k < gate_by_dof_.size(); ++k)
      gate_by_dof_[k] = math::chiSquareQuantile(config_.gate_probability, static_cast<int>(k));
  }
  return gate_by_dof_[dof];
}

// JCBB's search state: the pairings on the current branch, and the Cholesky factor L of their
// joint innovation covariance S with w = L^-1 nu, both grown by two rows per pairing (the joint
// Mahalanobis distance is |w|^2).
struct DataAssociation::Branch {
  struct Pair {
    Pairing pairing;
    LinearPairing q;
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

void DataAssociation::jcbb(const std::vector<std::vector<int>>& candidates,
                           const Eigen::MatrixXd& p, const Linearise& linearise, size_t i,
                           Branch& branch, std::vector<Pairing>& best, double& best_d2,
                           long& nodes) const {
  ++nodes;
  const size_t n = candidates.size();
  const size_t depth = branch.pairs.size();
  if (i == n) {
    const double d2 = branch.distance();
    if (depth > best.size() || (depth == best.size() && d2 < best_d2)) {
      best = branch.pairings();
      best_d2 = d2;
    }
    return;
  }
  // Bound: even pairing every remaining observation cannot beat the best.
  if (depth + (n - i) < best.size()) return;
  // Budget: JCBB is exponential in the worst case (many parallel walls); past the budget the best
  // hypothesis found so far stands.
  if (nodes > config_.jcbb_max_nodes) return;
  const Eigen::Matrix3d prr = p.topLeftCorner<3, 3>();
  for (int lm : candidates[i]) {
    bool used = false;
    if (!config_.share_landmarks)
      for (const auto& b : branch.pairs) used |= b.pairing.lm == lm;
    if (used) continue;
    Branch::Pair np{{static_cast<int>(i), lm}, linearise(static_cast<int>(i), lm)};
    const LinearPairing& q = np.q;
    // The new pairing's covariance with each on the branch (the 2 x 2 blocks of H P H^T) and its
    // own.
    const auto cross = [&](const LinearPairing& a, const LinearPairing& c) {
      Eigen::Matrix2d sac = a.hr * prr * c.hr.transpose();
      if (c.col >= 0) sac += a.hr * p.block<3, 2>(0, c.col) * c.hl.transpose();
      if (a.col >= 0) {
        sac += a.hl * p.block<2, 3>(a.col, 0) * c.hr.transpose();
        if (c.col >= 0) sac += a.hl * p.block<2, 2>(a.col, c.col) * c.hl.transpose();
      }
      return sac;
    };
    const int m2 = 2 * static_cast<int>(depth);
    Eigen::MatrixXd c(m2, 2);
    for (size_t k = 0; k < depth; ++k) c.middleRows<2>(2 * k) = cross(branch.pairs[k].q, q);
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
      const int rows = std::max<int>(dof, 2 * static_cast<int>(n));
      branch.l.conservativeResize(rows, rows);
      branch.w.conservativeResize(rows);
    }
    if (depth > 0) branch.l.block(m2, 0, 2, m2) = bt;
    branch.l.block<2, 2>(m2, m2) = e.matrixL();
    branch.w.segment<2>(m2) = wq;
    branch.pairs.push_back(std::move(np));
    branch.d2.push_back(d2);
    jcbb(candidates, p, linearise, i + 1, branch, best, best_d2, nodes);
    branch.pairs.pop_back();
    branch.d2.pop_back();
  }
  // The null hypothesis for observation i (new or spurious line).
  if (depth + (n - i - 1) >= best.size())
    jcbb(candidates, p, linearise, i + 1, branch, best, best_d2, nodes);
}

std::vector<int> DataAssociation::associate(int observations, int landmarks,
                                            const Eigen::MatrixXd& p,
                                            const Linearise& linearise) const {
  const double gate2 = gate(2);
  // Each observation's individually compatible landmarks, most compatible first: JCBB then finds
  // good hypotheses early and prunes more.
  std::vector<std::vector<int>> candidates(observations);
  for (int i = 0; i < observations; ++i) {
    std::vector<std::pair<double, int>> found;
    for (int j = 0; j < landmarks; ++j) {
      const double d2 = mahalanobis(linearise(i, j), p);
      if (d2 <= gate2) found.emplace_back(d2, j);
    }
    std::stable_sort(found.begin(), found.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& f : found) candidates[i].push_back(f.second);
  }
  std::vector<int> out(observations, -1);
  if (config_.method == Association::kNearestNeighbour) {
    for (int i = 0; i < observations; ++i)
      if (!candidates[i].empty()) out[i] = candidates[i].front();
    return out;
  }
  Branch branch;
  std::vector<Pairing> best;
  double best_d2 = std::numeric_limits<double>::infinity();
  long nodes = 0;
  jcbb(candidates, p, linearise, 0, branch, best, best_d2, nodes);
  for (const auto& b : best) out[b.obs] = b.lm;
  return out;
}

}  // namespace adaptive_perception::slam
