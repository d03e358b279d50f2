#include "adaptive_perception/places/sequence_matcher.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace adaptive_perception::places {

namespace {
void need(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("SequenceMatcherConfig: " + what);
}
}  // namespace

void SequenceMatcherConfig::validate() const {
  need(sequence_frames >= 1 && sequence_frames <= 1000, "sequence_frames must be in [1, 1000]");
  need(std::isfinite(min_velocity) && min_velocity > 0.0 && min_velocity <= 100.0,
       "min_velocity must be in (0, 100]");
  need(std::isfinite(max_velocity) && max_velocity >= min_velocity && max_velocity <= 100.0,
       "max_velocity must be in [min_velocity, 100]");
  need(velocity_steps >= 1 && velocity_steps <= 100, "velocity_steps must be in [1, 100]");
  need(contrast_window_frames >= 2 && contrast_window_frames <= 100000,
       "contrast_window_frames must be in [2, 100000]");
}

SequenceMatcher::SequenceMatcher(SequenceMatcherConfig config) : config_(config) {
  config_.validate();
}

void SequenceMatcher::reset() {
  history_.clear();
  queries_ = 0;
}

std::vector<float> SequenceMatcher::enhance(const std::vector<float>& d) const {
  return contrastEnhance(d, config_.contrast_window_frames);
}

std::vector<float> contrastEnhance(const std::vector<float>& d, int window_frames) {
  const int n = static_cast<int>(d.size());
  std::vector<double> s(n + 1, 0.0), q(n + 1, 0.0);
  for (int j = 0; j < n; ++j) {
    s[j + 1] = s[j] + d[j];
    q[j + 1] = q[j] + static_cast<double>(d[j]) * d[j];
  }
  const int w = std::min(n, window_frames);
  std::vector<float> out(n);
  for (int j = 0; j < n; ++j) {
    const int a = std::clamp(j - w / 2, 0, n - w), b = a + w;
    const double mean = (s[b] - s[a]) / w;
    const double var = std::max(0.0, (q[b] - q[a]) / w - mean * mean);
    // A window of equal distances has no contrast: a small floor keeps it at 0 instead of inf.
    const double sd = std::sqrt(var) + 1e-6 * (std::abs(mean) + 1.0);
    out[j] = static_cast<float>((d[j] - mean) / sd);
  }
  return out;
}

const std::vector<float>& SequenceMatcher::add(const std::vector<float>& distances) {
  if (distances.empty()) throw std::invalid_argument("SequenceMatcher::add: no reference");
  if (!history_.empty() && distances.size() != history_.front().size())
    throw std::invalid_argument("SequenceMatcher::add: " + std::to_string(distances.size()) +
                                " distances, the earlier queries had " +
                                std::to_string(history_.front().size()));
  for (float v : distances)
    if (!std::isfinite(v)) throw std::invalid_argument("SequenceMatcher::add: non-finite distance");
  history_.push_front(enhance(distances));
  while (static_cast<int>(history_.size()) > config_.sequence_frames) history_.pop_back();
  ++queries_;

  const int n = static_cast<int>(distances.size());
  const int len = static_cast<int>(history_.size());
  scores_.assign(n, std::numeric_limits<float>::infinity());
  sum_.resize(n);
  const int steps = config_.velocity_steps;
  for (int vi = 0; vi < steps; ++vi) {
    // Spread evenly in log(v): a query twice as fast as the reference and one half as fast
    // are equally far from the same speed.
    const double v = steps == 1 ? config_.min_velocity
                                : config_.min_velocity *
                                      std::pow(config_.max_velocity / config_.min_velocity,
                                               static_cast<double>(vi) / (steps - 1));
    std::fill(sum_.begin(), sum_.end(), 0.0f);
    for (int k = 0; k < len; ++k) {
      const long shift = std::lround(v * k);
      if (shift >= n) break;
      const float* h = history_[k].data();
      for (int j = static_cast<int>(shift); j < n; ++j) {
        sum_[j] += h[j - shift];
      }
    }
    const float inv_len = 1.0f / static_cast<float>(len);
    for (int j = 0; j < n; ++j) scores_[j] = std::min(scores_[j], sum_[j] * inv_len);
  }
  return scores_;
}

}  // namespace adaptive_perception::places
