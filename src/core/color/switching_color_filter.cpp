#include "adaptive_perception/color/switching_color_filter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "adaptive_perception/config/enum_names.h"

namespace adaptive_perception::color {

const config::EnumNames<ModeMixing>& modeMixings() {
  static const config::EnumNames<ModeMixing> names(
      "mixing", {{ModeMixing::kBestMode, "best_mode"}, {ModeMixing::kImm, "imm"}});
  return names;
}

ModeMixing parseModeMixing(const std::string& name) { return modeMixings().parse(name); }

void SwitchingFilterConfig::validate() const {
  if (!(mode_stay_probability > 0.0 && mode_stay_probability <= 1.0))
    throw std::invalid_argument("mode_stay_probability = " + std::to_string(mode_stay_probability) +
                                " (allowed: 0 < p <= 1)");
  if (!(imm_prior_pull_per_s >= 0.0 && std::isfinite(imm_prior_pull_per_s)))
    throw std::invalid_argument("imm_prior_pull_per_s = " + std::to_string(imm_prior_pull_per_s) +
                                " (allowed: >= 0)");
}

SwitchingColorFilter::SwitchingColorFilter(const std::vector<LightingPrior>& priors,
                                           const ColorModelConfig& model_config,
                                           const SwitchingFilterConfig& config)
    : priors_(priors) {
  if (priors_.empty())
    throw std::invalid_argument("SwitchingColorFilter: needs at least one prior");
  for (const auto& p : priors_) {
    modes_.emplace_back(p, model_config);
    names_.push_back(p.name);
  }
  setConfig(config);
  reset();
}

void SwitchingColorFilter::setConfig(const SwitchingFilterConfig& config) {
  config.validate();
  config_ = config;
  const int k = numModes();
  transition_ =
      Eigen::MatrixXd::Constant(k, k, k > 1 ? (1.0 - config.mode_stay_probability) / (k - 1) : 0.0);
  transition_.diagonal().setConstant(k > 1 ? config.mode_stay_probability : 1.0);
}

void SwitchingColorFilter::setDrift(double drift) {
  for (size_t j = 0; j < modes_.size(); ++j) {
    ColorModelConfig c = modes_[j].config();
    c.drift_std_per_sqrt_s = drift;
    c.validate();
    ColorFilter f(priors_[j], c);
    f.kalman().reset(modes_[j].mean(), modes_[j].cov());
    modes_[j] = f;
  }
}

std::vector<double> SwitchingColorFilter::predictedModeProbabilities() const {
  std::vector<double> p(modes_.size(), 0.0);
  for (size_t j = 0; j < modes_.size(); ++j)
    for (size_t i = 0; i < modes_.size(); ++i) p[j] += transition_(i, j) * probs_[i];
  return p;
}

void SwitchingColorFilter::reset() {
  for (size_t j = 0; j < modes_.size(); ++j) modes_[j].reset(priors_[j]);
  probs_.assign(modes_.size(), 1.0 / static_cast<double>(modes_.size()));
  active_ = 0;
}

void SwitchingColorFilter::predict(double dt_s) {
  if (config_.mixing == ModeMixing::kBestMode) {
    modes_[active_].predict(dt_s);
    return;
  }
  // IMM mixing: mode j starts from sum_i mu(i|j) x_i, mu(i|j) = T(i,j) p_i / sum_i T(i,j) p_i.
  const int k = numModes();
  std::vector<Eigen::VectorXd> means(k);
  std::vector<Eigen::MatrixXd> covs(k);
  for (int j = 0; j < k; ++j) {
    double norm = 0.0;
    for (int i = 0; i < k; ++i) norm += transition_(i, j) * probs_[i];
    Eigen::VectorXd m = Eigen::VectorXd::Zero(modes_[j].mean().size());
    std::vector<double> w(k);
    for (int i = 0; i < k; ++i) {
      w[i] = norm > 0 ? transition_(i, j) * probs_[i] / norm : (i == j ? 1.0 : 0.0);
      m += w[i] * modes_[i].mean();
    }
    Eigen::MatrixXd c = Eigen::MatrixXd::Zero(m.size(), m.size());
    for (int i = 0; i < k; ++i) {
      const Eigen::VectorXd d = modes_[i].mean() - m;
      c += w[i] * (modes_[i].cov() + d * d.transpose());
    }
    means[j] = m;
    covs[j] = c;
  }
  const double keep = std::exp(-config_.imm_prior_pull_per_s * std::max(0.0, dt_s));
  for (int j = 0; j < k; ++j) {
    // Mean reversion towards the mode's prior: theta' = mu0 + keep (theta - mu0), then the drift.
    const Eigen::VectorXd m = priors_[j].mean + keep * (means[j] - priors_[j].mean);
    modes_[j].kalman().reset(m, keep * keep * covs[j]);
    modes_[j].predict(dt_s);
  }
}

double SwitchingColorFilter::update(const ColorObservation& obs) {
  const int k = numModes();
  std::vector<int> idx;
  Eigen::VectorXd z;
  Eigen::MatrixXd noise;
  modes_[0].observationOf(obs, &idx, &z, &noise);
  if (idx.empty()) return 0.0;
  std::vector<double> ll(k), prior(k, 0.0);
  double max_ll = -1e300;
  for (int j = 0; j < k; ++j) {
    ll[j] = modes_[j].predictiveLogLikelihood(obs);
    max_ll = std::max(max_ll, ll[j]);
    for (int i = 0; i < k; ++i) prior[j] += transition_(i, j) * probs_[i];
  }
  double total = 0.0;
  for (int j = 0; j < k; ++j) {
    probs_[j] = prior[j] * std::exp(ll[j] - max_ll);
    total += probs_[j];
  }
  for (double& p : probs_) p /= total;
  active_ = static_cast<int>(std::max_element(probs_.begin(), probs_.end()) - probs_.begin());
  if (config_.mixing == ModeMixing::kBestMode) {
    modes_[active_].update(obs);
  } else {
    for (auto& m : modes_) m.update(obs);
  }
  return max_ll + std::log(total);
}

}  // namespace adaptive_perception::color
