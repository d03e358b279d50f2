#include "adaptive_perception/math/kalman_filter.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>
#include <string>

namespace adaptive_perception::math {

namespace {
constexpr double kLog2Pi = 1.8378770664093454836;

void checkSquare(const Eigen::MatrixXd& m, int n, const char* what) {
  if (m.rows() != n || m.cols() != n) {
    throw std::invalid_argument(std::string("KalmanFilter: ") + what + " is " +
                                std::to_string(m.rows()) + "x" + std::to_string(m.cols()) +
                                ", expected " + std::to_string(n) + "x" + std::to_string(n));
  }
}
}  // namespace

KalmanFilter::KalmanFilter(Eigen::VectorXd mean, Eigen::MatrixXd cov) {
  reset(std::move(mean), std::move(cov));
}

void KalmanFilter::reset(Eigen::VectorXd mean, Eigen::MatrixXd cov) {
  checkSquare(cov, static_cast<int>(mean.size()), "covariance");
  mean_ = std::move(mean);
  cov_ = std::move(cov);
}

void KalmanFilter::predict(const Eigen::MatrixXd& drift_cov) {
  checkSquare(drift_cov, dim(), "drift covariance");
  cov_ += drift_cov;
}

void KalmanFilter::predict(const Eigen::MatrixXd& a, const Eigen::MatrixXd& drift_cov) {
  checkSquare(a, dim(), "transition matrix");
  checkSquare(drift_cov, dim(), "drift covariance");
  mean_ = a * mean_;
  cov_ = a * cov_ * a.transpose() + drift_cov;
}

double KalmanFilter::predictiveLogLikelihood(const Eigen::MatrixXd& h, const Eigen::VectorXd& z,
                                             const Eigen::MatrixXd& obs_cov) const {
  const Eigen::MatrixXd s = h * cov_ * h.transpose() + obs_cov;
  const Eigen::LLT<Eigen::MatrixXd> llt(s);
  if (llt.info() != Eigen::Success) {
    throw std::runtime_error("KalmanFilter: innovation covariance is not positive definite");
  }
  const Eigen::VectorXd y = llt.matrixL().solve(z - h * mean_);
  const double log_det = 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
  return -0.5 * (static_cast<double>(z.size()) * kLog2Pi + log_det + y.squaredNorm());
}

KalmanUpdateResult KalmanFilter::updateImpl(const Eigen::MatrixXd& h, const Eigen::VectorXd& z,
                                            const Eigen::MatrixXd& obs_cov, bool joseph) {
  const int m = static_cast<int>(z.size());
  if (h.rows() != m || h.cols() != dim()) {
    throw std::invalid_argument("KalmanFilter: H is " + std::to_string(h.rows()) + "x" +
                                std::to_string(h.cols()) + ", expected " + std::to_string(m) + "x" +
                                std::to_string(dim()));
  }
  checkSquare(obs_cov, m, "observation covariance");
  const Eigen::VectorXd innovation = z - h * mean_;
  const Eigen::MatrixXd pht = cov_ * h.transpose();
  const Eigen::MatrixXd s = h * pht + obs_cov;
  const Eigen::LLT<Eigen::MatrixXd> llt(s);
  if (llt.info() != Eigen::Success) {
    throw std::runtime_error("KalmanFilter: innovation covariance is not positive definite");
  }
  KalmanUpdateResult result;
  const Eigen::VectorXd y = llt.matrixL().solve(innovation);
  result.innovation_mahalanobis_sq = y.squaredNorm();
  const double log_det = 2.0 * llt.matrixL().toDenseMatrix().diagonal().array().log().sum();
  result.log_likelihood = -0.5 * (m * kLog2Pi + log_det + result.innovation_mahalanobis_sq);

  // K = P H^T S^-1, computed as (S^-1 H P)^T since S and P are symmetric.
  const Eigen::MatrixXd k = llt.solve(pht.transpose()).transpose();
  mean_ += k * innovation;
  const Eigen::MatrixXd i_kh = Eigen::MatrixXd::Identity(dim(), dim()) - k * h;
  if (joseph) {
    cov_ = i_kh * cov_ * i_kh.transpose() + k * obs_cov * k.transpose();
  } else {
    cov_ = i_kh * cov_;
  }
  cov_ = 0.5 * (cov_ + cov_.transpose());
  return result;
}

KalmanUpdateResult KalmanFilter::update(const Eigen::MatrixXd& h, const Eigen::VectorXd& z,
                                        const Eigen::MatrixXd& obs_cov) {
  return updateImpl(h, z, obs_cov, true);
}

KalmanUpdateResult KalmanFilter::updateStandardForm(const Eigen::MatrixXd& h,
                                                    const Eigen::VectorXd& z,
                                                    const Eigen::MatrixXd& obs_cov) {
  return updateImpl(h, z, obs_cov, false);
}

KalmanUpdateResult KalmanFilter::updatePartial(const std::vector<int>& observed_idx,
                                               const Eigen::VectorXd& z,
                                               const Eigen::MatrixXd& obs_cov) {
  return update(selectionMatrix(dim(), observed_idx), z, obs_cov);
}

Eigen::MatrixXd selectionMatrix(int n, const std::vector<int>& observed_idx) {
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(observed_idx.size(), n);
  for (size_t r = 0; r < observed_idx.size(); ++r) {
    if (observed_idx[r] < 0 || observed_idx[r] >= n) {
      throw std::out_of_range("selectionMatrix: index " + std::to_string(observed_idx[r]) +
                              " outside a state of dimension " + std::to_string(n));
    }
    h(r, observed_idx[r]) = 1.0;
  }
  return h;
}

}  // namespace adaptive_perception::math
