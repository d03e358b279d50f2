#pragma once
// Linear Kalman filter over a state x ~ N(mean, cov).
//
//   predict:  x_k = A x_{k-1} + w,   w ~ N(0, R)      (A = I for a pure drift / random walk)
//   update:   z_k = H x_k + v,       v ~ N(0, Q)
//
// The covariance update uses the Joseph form (I-KH) P (I-KH)^T + K Q K^T, which stays symmetric
// positive semi-definite under round-off. A partial observation observes only some state components
// directly (H = rows of the identity); it equals conditioning the joint Gaussian of state and
// observation.
#include <Eigen/Core>
#include <vector>

namespace adaptive_perception::math {

struct KalmanUpdateResult {
  /// log N(z; H mean_pred, H P_pred H^T + Q): the innovation (predictive) log-likelihood.
  double log_likelihood = 0.0;
  /// Squared Mahalanobis distance of the innovation.
  double innovation_mahalanobis_sq = 0.0;
};

class KalmanFilter {
 public:
  KalmanFilter() = default;
  KalmanFilter(Eigen::VectorXd mean, Eigen::MatrixXd cov);

  const Eigen::VectorXd& mean() const { return mean_; }
  const Eigen::MatrixXd& cov() const { return cov_; }
  int dim() const { return static_cast<int>(mean_.size()); }
  void reset(Eigen::VectorXd mean, Eigen::MatrixXd cov);

  /// Random-walk prediction: mean unchanged, cov += drift_cov.
  void predict(const Eigen::MatrixXd& drift_cov);
  /// General linear prediction: mean = A mean, cov = A cov A^T + drift_cov.
  void predict(const Eigen::MatrixXd& a, const Eigen::MatrixXd& drift_cov);

  /// Full linear update, Joseph-form covariance. Throws std::invalid_argument on size mismatch and
  /// std::runtime_error when the innovation covariance is not positive definite.
  KalmanUpdateResult update(const Eigen::MatrixXd& h, const Eigen::VectorXd& z,
                            const Eigen::MatrixXd& obs_cov);
  /// Same update with the textbook covariance (I - K H) P; kept for tests and comparison.
  KalmanUpdateResult updateStandardForm(const Eigen::MatrixXd& h, const Eigen::VectorXd& z,
                                        const Eigen::MatrixXd& obs_cov);
  /// Direct observation of the components `observed_idx` only: z = x[observed_idx] + v, v ~ N(0,
  /// obs_cov).
  KalmanUpdateResult updatePartial(const std::vector<int>& observed_idx, const Eigen::VectorXd& z,
                                   const Eigen::MatrixXd& obs_cov);

  /// The innovation log-likelihood an update with these arguments would give, without updating.
  double predictiveLogLikelihood(const Eigen::MatrixXd& h, const Eigen::VectorXd& z,
                                 const Eigen::MatrixXd& obs_cov) const;

 private:
  KalmanUpdateResult updateImpl(const Eigen::MatrixXd& h, const Eigen::VectorXd& z,
                                const Eigen::MatrixXd& obs_cov, bool joseph);
  Eigen::VectorXd mean_;
  Eigen::MatrixXd cov_;
};

/// H selecting `observed_idx` out of a state of dimension n.
Eigen::MatrixXd selectionMatrix(int n, const std::vector<int>& observed_idx);

}  // namespace adaptive_perception::math
