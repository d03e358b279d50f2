#pragma once
// Weighted particle sets: log-weight normalisation, effective sample size and resampling.
//
// Resampling schemes (all return, for each new particle, the index of its parent):
//   kMultinomial  N independent draws from the weights (highest variance; reference only).
//   kStratified   one uniform draw inside each of N equal strata of [0, 1).
//   kSystematic   one uniform offset u ~ U[0, 1/N), then u + i/N: the "low-variance sampler" of
//                 Thrun, Burgard & Fox, Probabilistic Robotics, Table 4.4. All three keep the
//                 expected number of copies of particle i equal to N w_i; systematic has the least
//                 variance (the count of i is floor(N w_i) or ceil(N w_i)).
#include <cstddef>
#include <string>
#include <vector>

#include "adaptive_perception/math/rng.h"

namespace adaptive_perception::math {

enum class ResamplingScheme { kMultinomial, kStratified, kSystematic };

/// Parses "multinomial" | "stratified" | "systematic" | "low_variance" (= systematic). Throws
/// std::invalid_argument naming the allowed values otherwise.
ResamplingScheme parseResamplingScheme(const std::string& name);

/// Normalises log-weights in place to weights summing to one (log-sum-exp, safe for very negative
/// log-likelihoods). Returns the log of the normaliser. If every log-weight is -inf or NaN, the
/// weights become uniform and -inf is returned.
double normalizeLogWeights(const std::vector<double>& log_weights, std::vector<double>* weights);

/// 1 / sum w_i^2 of normalised weights.
double effectiveSampleSize(const std::vector<double>& weights);

/// Parent indices of `count` new particles drawn from normalised `weights`.
std::vector<std::size_t> resampleIndices(const std::vector<double>& weights, std::size_t count,
                                         ResamplingScheme scheme, Rng& rng);

/// A set of particles of any state type with normalised weights.
template <typename State>
class ParticleSet {
 public:
  ParticleSet() = default;
  explicit ParticleSet(std::vector<State> states)
      : states_(std::move(states)), weights_(states_.size(), 1.0 / states_.size()) {}

  std::size_t size() const { return states_.size(); }
  std::vector<State>& states() { return states_; }
  const std::vector<State>& states() const { return states_; }
  const std::vector<double>& weights() const { return weights_; }

  /// Sets the weights from unnormalised log-weights; returns the log normaliser.
  double setLogWeights(const std::vector<double>& log_weights) {
    return normalizeLogWeights(log_weights, &weights_);
  }
  double effectiveSampleSize() const { return math::effectiveSampleSize(weights_); }

  /// Replaces the set by `count` resampled particles with uniform weights.
  void resample(ResamplingScheme scheme, Rng& rng, std::size_t count = 0) {
    if (count == 0) count = states_.size();
    const auto idx = resampleIndices(weights_, count, scheme, rng);
    std::vector<State> next;
    next.reserve(count);
    for (std::size_t i : idx) next.push_back(states_[i]);
    states_ = std::move(next);
    weights_.assign(count, 1.0 / static_cast<double>(count));
  }

 private:
  std::vector<State> states_;
  std::vector<double> weights_;
};

}  // namespace adaptive_perception::math
