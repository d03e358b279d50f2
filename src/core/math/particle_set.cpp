#include "adaptive_perception/math/particle_set.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "adaptive_perception/config/enum_names.h"

namespace adaptive_perception::math {

ResamplingScheme parseResamplingScheme(const std::string& name) {
  static const config::EnumNames<ResamplingScheme> names(
      "resampling scheme",
      {{ResamplingScheme::kMultinomial, "multinomial"},
       {ResamplingScheme::kStratified, "stratified"},
       {ResamplingScheme::kSystematic, "systematic"}},
      {{ResamplingScheme::kSystematic, "low_variance"}});
  return names.parse(name);
}

double normalizeLogWeights(const std::vector<double>& log_weights, std::vector<double>* weights) {
  const std::size_t n = log_weights.size();
  weights->resize(n);
  double max_lw = -std::numeric_limits<double>::infinity();
  for (double lw : log_weights)
    if (std::isfinite(lw) || lw == std::numeric_limits<double>::infinity())
      max_lw = std::max(max_lw, lw);
  if (n == 0) return max_lw;
  if (!std::isfinite(max_lw)) {
    std::fill(weights->begin(), weights->end(), 1.0 / static_cast<double>(n));
    return -std::numeric_limits<double>::infinity();
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double lw = log_weights[i];
    (*weights)[i] = std::isnan(lw) ? 0.0 : std::exp(lw - max_lw);
    sum += (*weights)[i];
  }
  for (double& w : *weights) w /= sum;
  return max_lw + std::log(sum);
}

double effectiveSampleSize(const std::vector<double>& weights) {
  double sq = 0.0;
  for (double w : weights) sq += w * w;
  return sq > 0.0 ? 1.0 / sq : 0.0;
}

std::vector<std::size_t> resampleIndices(const std::vector<double>& weights, std::size_t count,
                                         ResamplingScheme scheme, Rng& rng) {
  if (weights.empty()) throw std::invalid_argument("resampleIndices: no particles");
  std::vector<std::size_t> out;
  out.reserve(count);
  if (count == 0) return out;
  const double n = static_cast<double>(count);
  if (scheme == ResamplingScheme::kMultinomial) {
    std::vector<double> cdf(weights.size());
    double acc = 0.0;
    for (std::size_t i = 0; i < weights.size(); ++i) cdf[i] = (acc += weights[i]);
    for (std::size_t k = 0; k < count; ++k) {
      const double u = rng.uniform() * acc;
      auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
      out.push_back(std::min<std::size_t>(it - cdf.begin(), weights.size() - 1));
    }
    return out;
  }
  // Stratified and systematic: walk the CDF once with increasing pointers.
  const double offset = rng.uniform(0.0, 1.0 / n);
  double cum = weights[0];
  std::size_t i = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const double u = scheme == ResamplingScheme::kSystematic
                         ? offset + static_cast<double>(k) / n
                         : (static_cast<double>(k) + rng.uniform()) / n;
    while (u > cum && i + 1 < weights.size()) cum += weights[++i];
    out.push_back(i);
  }
  return out;
}

}  // namespace adaptive_perception::math
