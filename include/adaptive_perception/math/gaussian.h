#pragma once
// Multivariate Gaussian N(mean, cov) with log-density through a Cholesky factor, block marginals
// and conditionals, and sampling.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <string>
#include <vector>

#include "adaptive_perception/math/rng.h"

namespace adaptive_perception::math {

/// Why `cov` cannot be a Gaussian's covariance, or "" when it can: not square, a non-finite entry
/// (named by its row and column), not symmetric (Eigen's isApprox with the transpose, relative
/// precision 1e-9: the largest difference is named), or not positive definite (its Cholesky
/// factorisation fails). The one test of a covariance: Gaussian's constructor and every node's
/// pose-with-covariance input apply it.
std::string covarianceProblem(const Eigen::MatrixXd& cov);

class Gaussian {
 public:
  Gaussian() = default;
  /// Throws std::invalid_argument when the sizes disagree or covarianceProblem(cov) names a
  /// problem.
  Gaussian(Eigen::VectorXd mean, Eigen::MatrixXd cov);

  int dim() const { return static_cast<int>(mean_.size()); }
  const Eigen::VectorXd& mean() const { return mean_; }
  const Eigen::MatrixXd& cov() const { return cov_; }

  /// log N(x; mean, cov) = -0.5 (d log 2pi + log|cov| + (x-mean)^T cov^-1 (x-mean)).
  double logDensity(const Eigen::VectorXd& x) const;
  /// Squared Mahalanobis distance (x-mean)^T cov^-1 (x-mean).
  double mahalanobisSq(const Eigen::VectorXd& x) const;

  /// The marginal over the components `idx` (in that order).
  Gaussian marginal(const std::vector<int>& idx) const;
  /// The conditional over the components NOT in `given_idx`, given x[given_idx] = values:
  /// mean_a + S_ab S_bb^-1 (values - mean_b), S_aa - S_ab S_bb^-1 S_ba. Returned components keep
  /// their original order.
  Gaussian conditional(const std::vector<int>& given_idx, const Eigen::VectorXd& values) const;

  /// One draw mean + L z, z ~ N(0, I).
  Eigen::VectorXd sample(Rng& rng) const;

 private:
  Eigen::VectorXd mean_;
  Eigen::MatrixXd cov_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  double log_norm_ = 0.0;  // -0.5 (d log 2pi + log|cov|)
};

/// The indices 0..n-1 not in `idx`, ascending.
std::vector<int> complementIndices(int n, const std::vector<int>& idx);
/// Rows/cols `rows` x `cols` of m.
Eigen::MatrixXd selectBlock(const Eigen::MatrixXd& m, const std::vector<int>& rows,
                            const std::vector<int>& cols);
Eigen::VectorXd selectRows(const Eigen::VectorXd& v, const std::vector<int>& rows);

}  // namespace adaptive_perception::math
