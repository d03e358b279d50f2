#include "adaptive_perception/math/gaussian.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace adaptive_perception::math {

namespace {
constexpr double kLog2Pi = 1.8378770664093454836;
}

Gaussian::Gaussian(Eigen::VectorXd mean, Eigen::MatrixXd cov)
    : mean_(std::move(mean)), cov_(std::move(cov)) {
  if (cov_.rows() != mean_.size() || cov_.cols() != mean_.size()) {
    throw std::invalid_argument("Gaussian: covariance is " + std::to_string(cov_.rows()) + "x" +
                                std::to_string(cov_.cols()) + " but the mean has " +
                                std::to_string(mean_.size()) + " components");
  }
  if (!cov_.isApprox(cov_.transpose(), 1e-9)) {
    throw std::invalid_argument("Gaussian: covariance is not symmetric");
  }
  llt_.compute(cov_);
  if (llt_.info() != Eigen::Success) {
    throw std::invalid_argument("Gaussian: covariance is not positive definite");
  }
  const double log_det = 2.0 * llt_.matrixL().toDenseMatrix().diagonal().array().log().sum();
  log_norm_ = -0.5 * (static_cast<double>(mean_.size()) * kLog2Pi + log_det);
}

double Gaussian::mahalanobisSq(const Eigen::VectorXd& x) const {
  const Eigen::VectorXd y = llt_.matrixL().solve(x - mean_);
  return y.squaredNorm();
}

double Gaussian::logDensity(const Eigen::VectorXd& x) const {
  return log_norm_ - 0.5 * mahalanobisSq(x);
}

Gaussian Gaussian::marginal(const std::vector<int>& idx) const {
  return Gaussian(selectRows(mean_, idx), selectBlock(cov_, idx, idx));
}

Gaussian Gaussian::conditional(const std::vector<int>& given_idx,
                               const Eigen::VectorXd& values) const {
  if (static_cast<int>(values.size()) != static_cast<int>(given_idx.size())) {
    throw std::invalid_argument("Gaussian::conditional: " + std::to_string(values.size()) +
                                " values for " + std::to_string(given_idx.size()) + " indices");
  }
  const std::vector<int> rest = complementIndices(dim(), given_idx);
  const Eigen::MatrixXd s_ab = selectBlock(cov_, rest, given_idx);
  const Eigen::MatrixXd s_bb = selectBlock(cov_, given_idx, given_idx);
  const Eigen::LLT<Eigen::MatrixXd> llt_bb(s_bb);
  const Eigen::VectorXd mean =
      selectRows(mean_, rest) + s_ab * llt_bb.solve(values - selectRows(mean_, given_idx));
  Eigen::MatrixXd cov = selectBlock(cov_, rest, rest) - s_ab * llt_bb.solve(s_ab.transpose());
  cov = 0.5 * (cov + cov.transpose());
  return Gaussian(mean, cov);
}

Eigen::VectorXd Gaussian::sample(Rng& rng) const {
  Eigen::VectorXd z(mean_.size());
  for (int i = 0; i < z.size(); ++i) z[i] = rng.gaussian();
  return mean_ + llt_.matrixL() * z;
}

std::vector<int> complementIndices(int n, const std::vector<int>& idx) {
  std::vector<bool> taken(n, false);
  for (int i : idx) {
    if (i < 0 || i >= n)
      throw std::out_of_range("index " + std::to_string(i) + " outside 0.." +
                              std::to_string(n - 1));
    taken[i] = true;
  }
  std::vector<int> rest;
  for (int i = 0; i < n; ++i)
    if (!taken[i]) rest.push_back(i);
  return rest;
}

Eigen::MatrixXd selectBlock(const Eigen::MatrixXd& m, const std::vector<int>& rows,
                            const std::vector<int>& cols) {
  Eigen::MatrixXd out(rows.size(), cols.size());
  for (size_t r = 0; r < rows.size(); ++r)
    for (size_t c = 0; c < cols.size(); ++c) out(r, c) = m(rows[r], cols[c]);
  return out;
}

Eigen::VectorXd selectRows(const Eigen::VectorXd& v, const std::vector<int>& rows) {
  Eigen::VectorXd out(rows.size());
  for (size_t r = 0; r < rows.size(); ++r) out[r] = v[rows[r]];
  return out;
}

}  // namespace adaptive_perception::math
