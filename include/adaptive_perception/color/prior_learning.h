#pragma once
// Learning lighting priors from earlier environments (section III-B, eq. 10).
//
// Each data set j is the sequence of per-image colour statistics recorded in one environment. The
// hierarchical normal model: theta_j ~ N(mu, Sigma) (the environment's lighting), and each image
// mean v_jt ~ N(theta_j, r_jt) with r_jt the filter's own observation noise (nu, or nu/n + floor).
// Integrating theta_j out is closed form (the data set's evidence is Gaussian in mu with covariance
// Sigma + its observation noise), and the posterior mode of (mu, Sigma) under a weak conjugate
// hyperprior on Sigma (worth `hyper_prior_dof` pseudo-environments of spread `hyper_prior_std`,
// which keeps Sigma positive definite with few data sets) is found by EM: the E-step is each
// theta_j's Gaussian posterior N(m_j, V_j), the M-step mu = mean of the m_j, Sigma = (kappa s^2 I +
// sum_j [(m_j - mu)(m_j - mu)^T + V_j]) / (N + kappa). Colours an image does not show are simply
// not observed in that image (exact, as the observation noise is diagonal). The pixel noise nu is
// the pooled within-image variance of the colours.
//
// Data sets are first grouped into K lighting clusters by k-means on their mean luminance (Y) per
// colour.
#include <cstdint>
#include <string>
#include <vector>

#include "adaptive_perception/color/color_model.h"

namespace adaptive_perception::color {

struct LightingDataSet {
  std::string name;
  std::vector<ColorObservation> frames;
};

struct PriorLearningConfig {
  int max_iterations = 500;
  double tolerance = 1e-6;       // relative change of mu and Sigma that ends EM
  double hyper_prior_dof = 1.0;  // kappa: the hyperprior's weight, in pseudo-environments
  double hyper_prior_std = 4.0;  // s: the hyperprior's per-component spread, 8-bit levels
  void validate() const;
};

/// Per data set, the mean Y of each modelled colour (over images that show it; the mean over all
/// data sets where it never appears). Rows: data sets.
Eigen::MatrixXd lumaFeatures(const std::vector<LightingDataSet>& sets,
                             const ColorModelConfig& config);

/// k-means (k-means++ seeding from `seed`, Lloyd iterations) of the rows of `features`; returns the
/// cluster of each row, clusters ordered by increasing mean of their centre (0 = darkest).
std::vector<int> kMeans(const Eigen::MatrixXd& features, int k, std::uint64_t seed);

/// The posterior mode of (mu0, Sigma0) given the data sets (eq. 10). Throws std::invalid_argument
/// when no set has an observed colour.
LightingPrior learnPrior(const std::vector<LightingDataSet>& sets,
                         const ColorModelConfig& model_config, const PriorLearningConfig& config,
                         const std::string& name);

/// The pooled within-image pixel variance per channel (nu of eq. 1).
Eigen::Vector3d pooledPixelNoise(const std::vector<LightingDataSet>& sets);

}  // namespace adaptive_perception::color
