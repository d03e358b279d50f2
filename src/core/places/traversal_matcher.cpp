#include "adaptive_perception/places/traversal_matcher.h"

#include "adaptive_perception/places/traversal_metrics.h"

#include <cmath>
#include <stdexcept>

namespace adaptive_perception::places {

namespace {
void need(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("TraversalMatcherConfig: " + what);
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
  return "thumbnail, gradient, chromaticity, layout, words, fused, sequence, route";
}

void TraversalMatcherConfig::validate() const {
  descriptor.validate();
  sequence.validate();
  route.validate();
  fusion.validate();
  need(isCueName(method) || method == "sequence" || method == "route" || method == "words",
       "method '" + method + "' is not one of " + methodNames());
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

void ReferenceTraversal::learnWords(const std::vector<cv::Mat>& sift,
                                    const BagOfWordsConfig& config) {
  if (static_cast<int>(sift.size()) != size())
    throw std::invalid_argument("ReferenceTraversal::learnWords: " + std::to_string(sift.size()) +
                                " SIFT matrices for " + std::to_string(size()) + " references");
  words_ = std::make_shared<const BagOfWords>(sift, config);
}

TraversalMatcher::TraversalMatcher(const ReferenceTraversal& references,
                                   TraversalMatcherConfig config)
    : refs_(references),
      config_(config),
      sequence_((config.validate(), config.sequence)),
      route_(config.route) {}

void TraversalMatcher::reset() {
  sequence_.reset();
  route_.reset();
}

double TraversalMatcher::confidence() const {
  return config_.method == "route" ? route_.confidence() : separation(scores_);
}

std::vector<float> cueDistances(const ReferenceTraversal& stored, const ImageDescriptors& query,
                                const std::array<double, kNumDescriptorKinds>& weights) {
  if (stored.size() == 0) throw std::invalid_argument("cueDistances: no stored image");
  std::vector<float> fused(stored.size(), 0.0f);
  double total = 0.0;
  for (int k = 0; k < kNumDescriptorKinds; ++k) {
    if (weights[k] <= 0.0) continue;
    std::vector<float> d =
        descriptorDistances(query.rows.at(k), stored.rows(static_cast<DescriptorKind>(k)));
    zScore(d);
    for (size_t j = 0; j < d.size(); ++j) fused[j] += static_cast<float>(weights[k]) * d[j];
    total += weights[k];
  }
  if (!(total > 0.0)) throw std::invalid_argument("cueDistances: every weight is 0");
  for (float& f : fused) f = static_cast<float>(f / total);
  return fused;
}

namespace {
// The bag of words' distances of the query as z-scores over the references.
std::vector<float> wordDistances(const ReferenceTraversal& refs, const ImageDescriptors& query) {
  if (!refs.words())
    throw std::invalid_argument("TraversalMatcher: the references have no bag of words");
  if (query.sift.cols != 128)
    throw std::invalid_argument("TraversalMatcher: the query has no SIFT descriptors");
  std::vector<float> d = refs.words()->distances(query.sift);
  zScore(d);
  return d;
}
}  // namespace

const std::vector<float>& TraversalMatcher::add(const ImageDescriptors& query) {
  if (refs_.size() == 0) throw std::invalid_argument("TraversalMatcher: no reference image");
  if (config_.method == "words") return scores_ = wordDistances(refs_, query);
  const bool sequence = config_.method == "sequence", route = config_.method == "route";
  const bool fused = sequence || route || config_.method == "fused";
  const FusionWeights& f = config_.fusion;
  scores_ = cueDistances(refs_, query, cueWeights(fused ? "fused" : config_.method, f));
  if (fused && f.words > 0.0) {
    const double rest = f.thumbnail + f.gradient + f.chromaticity;
    const std::vector<float> w = wordDistances(refs_, query);
    for (size_t j = 0; j < scores_.size(); ++j)
      scores_[j] = static_cast<float>((rest * scores_[j] + f.words * w[j]) / (rest + f.words));
  }
  if (sequence) return scores_ = sequence_.add(scores_);
  if (route) return scores_ = route_.add(scores_);
  return scores_;
}

}  // namespace adaptive_perception::places
