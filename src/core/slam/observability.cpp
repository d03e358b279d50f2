#include "adaptive_perception/slam/observability.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <stdexcept>
#include <string>

namespace adaptive_perception::slam {

void FisherInformation::add(const Eigen::MatrixXd& h, const Eigen::MatrixXd& s) {
  if (h.cols() != j_.rows() || s.rows() != h.rows() || s.cols() != h.rows())
    throw std::invalid_argument("FisherInformation::add: H is " + std::to_string(h.rows()) + "x" +
                                std::to_string(h.cols()) + ", S is " + std::to_string(s.rows()) +
                                "x" + std::to_string(s.cols()) + ", state dimension " +
                                std::to_string(j_.rows()));
  const Eigen::LLT<Eigen::MatrixXd> llt(s);
  if (llt.info() != Eigen::Success)
    throw std::invalid_argument("FisherInformation::add: S is not positive definite");
  j_ += h.transpose() * llt.solve(h);
}

ObservabilityAnalysis analyzeInformation(const Eigen::MatrixXd& j, double relative_tolerance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (j + j.transpose()));
  ObservabilityAnalysis out;
  out.eigenvalues = eig.eigenvalues();
  const double largest = out.eigenvalues.size() ? out.eigenvalues.cwiseAbs().maxCoeff() : 0.0;
  const double tol = relative_tolerance * largest;
  int zero = 0;
  for (int i = 0; i < out.eigenvalues.size(); ++i) zero += out.eigenvalues[i] <= tol;
  out.rank = static_cast<int>(out.eigenvalues.size()) - zero;
  out.null_space = eig.eigenvectors().leftCols(zero);  // ascending order: the zeros come first
  return out;
}

}  // namespace adaptive_perception::slam
