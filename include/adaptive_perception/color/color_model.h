#pragma once
// The two-level Gaussian colour model of Schulz & Fox (IROS 2004), section III.
//
// Lower level (eq. 1): the YUV value c of a pixel showing map colour m is N(c; theta[m], nu), nu
// diagonal and shared by all colours. Upper level (eqs. 2-6): the 3M-vector theta of all colour
// means ("the lighting condition") is Gaussian, N(mu, Sigma), tracked by a Kalman filter with
// random drift R per second. Observation per image: the mean YUV of the pixels of each map colour
// (given the pixel labels), a direct observation of theta's components; colours absent from the
// image are handled exactly by a partial observation update (the conditional-Gaussian regression of
// the paper's footnote 1).
//
// State layout: component 3*k + ch is channel ch (0 Y, 1 U, 2 V) of the k-th modelled colour
// (ColorModelConfig::classes[k]); helpers colorIndex()/componentIndex() name the offsets.
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/math/kalman_filter.h"

namespace adaptive_perception::color {

/// How the noise of an image's colour mean is modelled.
enum class ObservationNoise {
  kPixelNoise,          // nu, as in the paper's eq. (5): the mean is treated like one pixel
  kPixelNoiseOverCount  // nu / n + floor: a mean of n pixels is n times more certain, up to model
                        // error
};
/// The observation noise models' words: "pixel", "pixel_over_count".
const config::EnumNames<ObservationNoise>& observationNoises();
ObservationNoise parseObservationNoise(const std::string& name);

struct ColorModelConfig {
  /// green, white, pink, yellow, cyan (defined out of line: GCC 12 warns on the inline initializer
  /// list).
  static std::vector<std::uint8_t> defaultClasses();
  /// Map colour classes (world::ColorClass ids) in the state, in order. Default: the five colours
  /// of the field without a ball.
  std::vector<std::uint8_t> classes = defaultClasses();
  /// Lighting drift: R = drift_std_per_sqrt_s^2 * dt * I, in 8-bit levels per sqrt(second) (eq. 6).
  double drift_std_per_sqrt_s = 3.0;
  ObservationNoise observation_noise = ObservationNoise::kPixelNoiseOverCount;
  /// Variance added to nu / n for kPixelNoiseOverCount (shading, label errors), levels^2.
  double observation_noise_floor_var = 4.0;
  /// A colour enters an image's observation only with at least this many labelled pixels.
  int min_pixels_per_color = 20;
  /// A pixel whose Mahalanobis distance (eq. 9 covariance) to every colour exceeds this is
  /// "unknown" (255).
  double unknown_mahalanobis = 5.0;

  int numColors() const { return static_cast<int>(classes.size()); }
  int dim() const { return 3 * numColors(); }
  /// The position of a class id in `classes`, or -1.
  int colorIndex(std::uint8_t class_id) const;
  void validate() const;  // throws std::invalid_argument naming the field, value and allowed range
};

inline int componentIndex(int color_index, int channel) { return 3 * color_index + channel; }

/// Variance of an image's colour mean on one channel under the configured noise model: nu[channel],
/// or nu[channel] / count + floor.
double observationVariance(const ColorModelConfig& config, const Eigen::Vector3d& nu, int count,
                           int channel);

/// Per-colour statistics of one image: pixel count, YUV mean and per-channel variance of the
/// pixels.
struct ColorObservation {
  std::vector<int> counts;             // per modelled colour
  std::vector<Eigen::Vector3d> means;  // YUV
  std::vector<Eigen::Vector3d> variances;
};

/// Statistics of `yuv` (CV_8UC3: Y, U, V) over the pixels whose `labels` (CV_8UC1 class ids) name a
/// modelled colour; other labels (background, unmodelled) are skipped.
ColorObservation computeColorObservation(const cv::Mat& yuv, const cv::Mat& labels,
                                         const ColorModelConfig& config);

/// A lighting prior (mu0, Sigma0) over the 3M colour means plus the pixel noise nu; what
/// config/color_priors/*.yaml hold.
struct LightingPrior {
  std::string name;
  std::vector<std::string> color_names;  // one per modelled colour, world::colorClassName()
  Eigen::VectorXd mean;                  // 3M
  Eigen::MatrixXd cov;                   // 3M x 3M
  Eigen::Vector3d pixel_noise_var{25.0, 9.0, 9.0};  // nu (diagonal), levels^2

  /// Loads a prior; throws std::runtime_error naming the file (and line) on any problem.
  static LightingPrior loadYaml(const std::string& path);
  /// Writes atomically (io::writeTextFileAtomically: a temporary beside path, renamed over it).
  void saveYaml(const std::string& path) const;
  /// The same prior with every cross-colour covariance block set to zero.
  LightingPrior independent() const;
  /// Checks sizes against `config` and that cov is symmetric positive definite.
  void validate(const ColorModelConfig& config) const;
};

/// Eq. (9) in closed form for fast per-pixel use: N(c; mu|m, Sigma|m + nu) for each colour, with
/// its inverse covariance and log normaliser precomputed.
class PixelClassifier {
 public:
  PixelClassifier() = default;
  PixelClassifier(const std::vector<Eigen::Vector3d>& means,
                  const std::vector<Eigen::Matrix3d>& covs,
                  const std::vector<std::uint8_t>& classes, double unknown_mahalanobis);

  int numColors() const { return static_cast<int>(means_.size()); }
  /// log N(c; mu|m, Sigma|m + nu) of the k-th modelled colour.
  double logLikelihood(const Eigen::Vector3d& yuv, int k) const {
    return log_norms_[k] - 0.5 * mahalanobisSq(yuv, k);
  }
  double mahalanobisSq(const Eigen::Vector3d& yuv, int k) const {
    const Eigen::Vector3d d = yuv - means_[k];
    return d.dot(inv_covs_[k] * d);
  }
  /// Maximum-likelihood class id, or 255 (unknown) when the pixel is farther than the threshold
  /// from all.
  std::uint8_t classify(const Eigen::Vector3d& yuv) const;
  const std::vector<Eigen::Vector3d>& means() const { return means_; }
  const std::vector<Eigen::Matrix3d>& covs() const { return covs_; }
  const std::vector<Eigen::Matrix3d>& inverseCovs() const { return inv_covs_; }
  /// log of the k-th colour's Gaussian normaliser, -0.5 log((2 pi)^3 det Sigma).
  double logNorm(int k) const { return log_norms_[k]; }
  const std::vector<std::uint8_t>& classes() const { return classes_; }

 private:
  std::vector<Eigen::Vector3d> means_;
  std::vector<Eigen::Matrix3d> covs_, inv_covs_;
  std::vector<double> log_norms_;
  std::vector<std::uint8_t> classes_;
  double unknown_mahalanobis_sq_ = 16.0;
};

/// One Kalman filter over the lighting condition (eqs. 2-6).
class ColorFilter {
 public:
  ColorFilter(const LightingPrior& prior, const ColorModelConfig& config);

  const ColorModelConfig& config() const { return config_; }
  const Eigen::VectorXd& mean() const { return kf_.mean(); }
  const Eigen::MatrixXd& cov() const { return kf_.cov(); }
  const Eigen::Vector3d& pixelNoiseVar() const { return nu_; }
  void reset(const LightingPrior& prior);

  /// Eq. (6): Sigma += R dt.
  void predict(double dt_s);
  /// The observed components and their values/noise for an image's statistics; empty when no colour
  /// has enough pixels.
  void observationOf(const ColorObservation& obs, std::vector<int>* idx, Eigen::VectorXd* z,
                     Eigen::MatrixXd* noise) const;
  /// Eqs. (3)-(5) on the observed colours (partial observation). Returns the innovation
  /// log-likelihood, 0 when nothing was observed.
  double update(const ColorObservation& obs);
  /// The innovation log-likelihood an update would give (no change); 0 when nothing is observed.
  double predictiveLogLikelihood(const ColorObservation& obs) const;

  Eigen::Vector3d colorMean(int k) const { return kf_.mean().segment<3>(3 * k); }
  Eigen::Matrix3d colorCov(int k) const { return kf_.cov().block<3, 3>(3 * k, 3 * k); }
  /// Eq. (9) for every modelled colour under the current estimate.
  PixelClassifier classifier() const;
  math::KalmanFilter& kalman() { return kf_; }
  const math::KalmanFilter& kalman() const { return kf_; }

 private:
  ColorModelConfig config_;
  math::KalmanFilter kf_;
  Eigen::Vector3d nu_;
};

}  // namespace adaptive_perception::color
