#pragma once
// Switching Kalman filter over lighting (jump Markov model, section III-A.3): K lighting modes,
// each a ColorFilter started from its own learned prior, a first-order Markov chain over modes, and
// the mode posterior from each mode's innovation likelihood:
//   p(s_k = j | z_1:k) ∝ N(z_k; mode j's prediction) * sum_i T(i, j) p(s_{k-1} = i | z_1:k-1).
//
// Two ways to maintain the modes' filters:
//   kBestMode (default, as in the paper): only the mode that best explains the image (the MAP mode)
//   is
//     predicted and updated; the others keep their estimate, ready for the light to switch back.
//   kImm: interacting multiple model (Blom & Bar-Shalom): the filters are mixed by the transition
//     probabilities before prediction, and every mode is updated. IMM needs modes that differ in
//     their dynamics, or mixing merges them into one; here mode j's dynamics pull the lighting back
//     towards its own prior mean, theta' = mu0_j + e^(-r dt) (theta - mu0_j) + w, r =
//     imm_prior_pull_per_s.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "adaptive_perception/color/color_model.h"
#include "adaptive_perception/config/enum_names.h"

namespace adaptive_perception::color {

enum class ModeMixing { kBestMode, kImm };
/// The mode mixings' words: "best_mode", "imm".
const config::EnumNames<ModeMixing>& modeMixings();
ModeMixing parseModeMixing(const std::string& name);

struct SwitchingFilterConfig {
  /// Probability of staying in a mode from one image to the next; the rest is spread evenly over
  /// the other modes.
  double mode_stay_probability = 0.9;
  ModeMixing mixing = ModeMixing::kBestMode;
  /// kImm only: rate (1/s) at which a mode's dynamics pull the estimate towards its prior mean.
  double imm_prior_pull_per_s = 0.5;
  void validate() const;
};

class SwitchingColorFilter {
 public:
  /// One mode per prior. Throws std::invalid_argument on an empty prior list or a bad config.
  SwitchingColorFilter(const std::vector<LightingPrior>& priors,
                       const ColorModelConfig& model_config, const SwitchingFilterConfig& config);

  int numModes() const { return static_cast<int>(modes_.size()); }
  int activeMode() const { return active_; }
  const std::string& modeName(int j) const { return names_[j]; }
  const std::vector<double>& modeProbabilities() const { return probs_; }
  /// The mode probabilities one step ahead, before the next image: sum_i T(i, j) p_i.
  std::vector<double> predictedModeProbabilities() const;
  const ColorFilter& mode(int j) const { return modes_[j]; }
  /// The estimate used for classification: the active mode's filter.
  const ColorFilter& active() const { return modes_[active_]; }
  const ColorModelConfig& modelConfig() const { return modes_[0].config(); }
  void setConfig(const SwitchingFilterConfig& config);
  void setDrift(double drift_std_per_sqrt_s);

  /// Back to the priors, uniform mode probabilities.
  void reset();
  /// Time update by dt_s seconds.
  void predict(double dt_s);
  /// Measurement update with one image's statistics; returns the log-likelihood of the image's
  /// colour means under the mixture (0 when nothing was observed).
  double update(const ColorObservation& obs);

 private:
  std::vector<LightingPrior> priors_;
  std::vector<std::string> names_;
  std::vector<ColorFilter> modes_;
  std::vector<double> probs_;
  Eigen::MatrixXd transition_;  // T(i, j) = p(s_k = j | s_{k-1} = i)
  SwitchingFilterConfig config_;
  int active_ = 0;
};

}  // namespace adaptive_perception::color
