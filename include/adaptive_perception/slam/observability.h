#pragma once
// Observability of SLAM through the total Fisher information (Garulli et al. 2005, section 2.2,
// eqs. 13-18):
//   J = sum_i H_i^T S_i^-1 H_i,   S_i = H_i P_i|i-1 H_i^T + W_i          (eq. 14)
// A singular J means no Cramer-Rao bound: the eigenvectors of its zero eigenvalues span the
// unobservable directions (eq. 18: (1, 1) for the one-landmark monobot, a common shift of robot and
// map).
#include <Eigen/Core>

namespace adaptive_perception::slam {

/// Running sum of eq. 14.
class FisherInformation {
 public:
  explicit FisherInformation(int state_dim) : j_(Eigen::MatrixXd::Zero(state_dim, state_dim)) {}
  /// Adds H^T S^-1 H; throws std::invalid_argument on mismatched sizes or a non positive definite
  /// S.
  void add(const Eigen::MatrixXd& h, const Eigen::MatrixXd& s);
  const Eigen::MatrixXd& matrix() const { return j_; }

 private:
  Eigen::MatrixXd j_;
};

struct ObservabilityAnalysis {
  int rank = 0;
  Eigen::VectorXd eigenvalues;  // ascending
  /// Unit eigenvectors of the eigenvalues below the tolerance (the unobservable directions).
  Eigen::MatrixXd null_space;
};

/// Rank and null space of a symmetric information matrix; eigenvalues below
/// relative_tolerance * (largest eigenvalue) count as zero.
ObservabilityAnalysis analyzeInformation(const Eigen::MatrixXd& j,
                                         double relative_tolerance = 1e-9);

}  // namespace adaptive_perception::slam
