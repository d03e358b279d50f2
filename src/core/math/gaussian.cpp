#include "adaptive_perception/math/gaussian.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace adaptive_perception::math {

namespace {
constexpr double kLog2Pi = 1.8378770664093454836;

/// covarianceProblem() short of the Cholesky factorisation, which the caller does.
std::string shapeProblem(const Eigen::MatrixXd& cov) {
  if (cov.rows() != cov.cols())
    return "is " + std::to_string(cov.rows()) + "x" + std::to_string(cov.cols()) + ", not square";
  for (Eigen::Index i = 0; i < cov.rows(); ++i)
    for (Eigen::Index j = 0; j < cov.cols(); ++j)
      if (!std::isfinite(cov(i, j)))
        return "entry (" + std::to_string(i) + ", " + std::to_string(j) + ") is " +
               std::to_string(cov(i, j)) + ", not finite";
  if (!cov.isApprox(cov.transpose(), 1e-9)) {
    Eigen::Index i = 0, j = 0;
    (cov - cov.transpose()).cwiseAbs().maxCoeff(&i, &j);
    return "is not symmetric (entry (" + std::to_string(i) + ", " + std::to_string(j) + ") is " +
           std::to_string(cov(i, j)) + ", entry (" + std::to_string(j) + ", " + std::to_string(i) +
           ") " + std::to_string(cov(j, i)) + ")";
  }
  return "";
}
constexpr const char* kNotPositiveDefinite = "is not positive definite";
}  // namespace

std::string covarianceProblem(const Eigen::MatrixXd& cov) {
  const std::string problem = shapeProblem(cov);
  if (!problem.empty()) return problem;
  return Eigen::LLT<Eigen::MatrixXd>(cov).info() == Eigen::Success ? "" : kNotPositiveDefinite;
}

Gaussian::Gaussian(Eigen::VectorXd mean, Eigen::MatrixXd cov)
    : mean_(std::move(mean)), cov_(std::move(cov)) {
  if (cov_.rows() != mean_.size() || cov_.cols() != mean_.size()) {
    throw std::invalid_argument("Gaussian: covariance is " + std::to_string(cov_.rows()) + "x" +
                                std::to_string(cov_.cols()) + " but the mean has " +
                                std::to_string(mean_.size()) + " components");
  }
  const std::string problem = shapeProblem(cov_);
  if (!problem.empty()) throw std::invalid_argument("Gaussian: covariance " + problem);
  llt_.compute(cov_);
  if (llt_.info() != Eigen::Success)
    throw std::invalid_argument(std::string("Gaussian: covariance ") + kNotPositiveDefinite);
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
