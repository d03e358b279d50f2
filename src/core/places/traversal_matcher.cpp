#include "adaptive_perception/places/traversal_matcher.h"

#include <cmath>
#include <stdexcept>

namespace adaptive_perception::places {

namespace {
void need(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("TraversalMatcherConfig: " + what);
}

bool isCue(const std::string& m, DescriptorKind* kind) {
  for (int k = 0; k < kNumDescriptorKinds; ++k)
    if (m == descriptorName(static_cast<DescriptorKind>(k))) {
      *kind = static_cast<DescriptorKind>(k);
      return true;
    }
  return false;
}

/// In place: (v - mean) / std over the vector (std floored so equal values give 0).
void zScore(std::vector<float>& v) {
  double s = 0.0, q = 0.0;
  for (float x : v) {
    s += x;
    q += static_cast<double>(x) * x;
  }
  const double mean = s / v.size();
  const double sd = std::sqrt(std::max(0.0, q / v.size() - mean * mean)) + 1e-9;
  for (float& x : v) x = static_cast<float>((x - mean) / sd);
}
}  // namespace

const char* TraversalMatcherConfig::methodNames() {
  return "thumbnail, gradient, chromaticity, fused, sequence";
}

std::array<double, kNumDescriptorKinds> TraversalMatcherConfig::cueWeights() const {
  DescriptorKind k;
  if (isCue(method, &k)) {
    std::array<double, kNumDescriptorKinds> w{};
    w[static_cast<int>(k)] = 1.0;
    return w;
  }
  return {thumbnail_weight, gradient_weight, chromaticity_weight};
}

void TraversalMatcherConfig::validate() const {
  descriptor.validate();
  sequence.validate();
  DescriptorKind k;
  need(isCue(method, &k) || method == "fused" || method == "sequence",
       "method '" + method + "' is not one of " + methodNames());
  for (double w : {thumbnail_weight, gradient_weight, chromaticity_weight})
    need(std::isfinite(w) && w >= 0.0 && w <= 1000.0, "the *_weight fields must be in [0, 1000]");
  need(thumbnail_weight + gradient_weight + chromaticity_weight > 0.0,
       "at least one of thumbnail_weight, gradient_weight, chromaticity_weight must be > 0");
}

ReferenceTraversal::ReferenceTraversal(GlobalDescriptorConfig config) : config_(config) {
  config_.validate();
  for (int k = 0; k < kNumDescriptorKinds; ++k)
    rows_[k] = cv::Mat(0, config_.length(static_cast<DescriptorKind>(k)), CV_8UC1);
}

void ReferenceTraversal::add(const ImageDescriptors& d) {
  if (d.rows.size() != static_cast<size_t>(kNumDescriptorKinds))
    throw std::invalid_argument("ReferenceTraversal::add: expected one row per descriptor kind");
  for (int k = 0; k < kNumDescriptorKinds; ++k)
    if (d.rows[k].type() != CV_8UC1 || d.rows[k].rows != 1 || d.rows[k].cols != rows_[k].cols)
      throw std::invalid_argument("ReferenceTraversal::add: the " +
                                  descriptorName(static_cast<DescriptorKind>(k)) +
                                  " row does not match the traversal's settings");
  for (int k = 0; k < kNumDescriptorKinds; ++k) rows_[k].push_back(d.rows[k]);
}

TraversalMatcher::TraversalMatcher(const ReferenceTraversal& references,
                                   TraversalMatcherConfig config)
    : refs_(references), config_(config), sequence_((config.validate(), config.sequence)) {}

void TraversalMatcher::reset() { sequence_.reset(); }

std::vector<float> TraversalMatcher::fusedDistances(const ImageDescriptors& query) const {
  if (refs_.size() == 0) throw std::invalid_argument("TraversalMatcher: no reference image");
  const auto w = config_.cueWeights();
  std::vector<float> fused(refs_.size(), 0.0f);
  double total = 0.0;
  for (int k = 0; k < kNumDescriptorKinds; ++k) {
    if (w[k] <= 0.0) continue;
    std::vector<float> d =
        descriptorDistances(query.rows.at(k), refs_.rows(static_cast<DescriptorKind>(k)));
    zScore(d);
    for (size_t j = 0; j < d.size(); ++j) fused[j] += static_cast<float>(w[k]) * d[j];
    total += w[k];
  }
  for (float& f : fused) f = static_cast<float>(f / total);
  return fused;
}

const std::vector<float>& TraversalMatcher::add(const ImageDescriptors& query) {
  if (refs_.size() == 0) throw std::invalid_argument("TraversalMatcher: no reference image");
  DescriptorKind k;
  if (isCue(config_.method, &k)) {
    scores_ = descriptorDistances(query.rows.at(static_cast<int>(k)), refs_.rows(k));
    return scores_;
  }
  scores_ = fusedDistances(query);
  if (config_.method == "fused") return scores_;
  return sequence_.add(scores_);
}

}  // namespace adaptive_perception::places
