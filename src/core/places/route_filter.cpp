#include "adaptive_perception/places/route_filter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "adaptive_perception/places/sequence_matcher.h"

namespace adaptive_perception::places {

namespace {
void need(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("RouteFilterConfig: " + what);
}
bool probability(double p) { return std::isfinite(p) && p >= 0.0 && p <= 1.0; }
}  // namespace

void RouteFilterConfig::validate() const {
  need(std::isfinite(min_speed) && min_speed > 0.0 && min_speed <= 100.0,
       "min_speed must be in (0, 100]");
  need(std::isfinite(max_speed) && max_speed >= min_speed && max_speed <= 100.0,
       "max_speed must be in [min_speed, 100]");
  need(speed_steps >= 1 && speed_steps <= 50, "speed_steps must be in [1, 50]");
  need(probability(speed_change_probability), "speed_change_probability must be in [0, 1]");
  need(probability(stop_probability), "stop_probability must be in [0, 1]");
  need(probability(start_probability), "start_probability must be in [0, 1]");
  need(probability(jump_probability) && jump_probability < 1.0,
       "jump_probability must be in [0, 1)");
  need(std::isfinite(likelihood_gain) && likelihood_gain > 0.0 && likelihood_gain <= 100.0,
       "likelihood_gain must be in (0, 100]");
  need(contrast_window_frames == 0 ||
           (contrast_window_frames >= 2 && contrast_window_frames <= 100000),
       "contrast_window_frames must be 0 (no enhancement) or in [2, 100000]");
  need(confidence_radius_frames >= 0 && confidence_radius_frames <= 100000,
       "confidence_radius_frames must be in [0, 100000]");
  need(subframes >= 1 && subframes <= 16, "subframes must be in [1, 16]");
  need(std::isfinite(hub_prior_queries) && hub_prior_queries >= 0.0 && hub_prior_queries <= 1e6,
       "hub_prior_queries must be in [0, 1e6]");
}

RouteFilter::RouteFilter(RouteFilterConfig config) : config_(config) {
  config_.validate();
  speeds_ = {-1.0, 0.0};
  const int k = config_.speed_steps;
  for (int i = 0; i < k; ++i)
    speeds_.push_back(k == 1 ? config_.min_speed
                             : config_.min_speed * std::pow(config_.max_speed / config_.min_speed,
                                                            static_cast<double>(i) / (k - 1)));
}

void RouteFilter::reset() {
  joint_.clear();
  sum_.clear();
  sum_sq_.clear();
  posterior_.clear();
  scores_.clear();
  best_ = -1;
  confidence_ = 0.0;
  queries_ = 0;
}

std::vector<double> RouteFilter::predict(const std::vector<double>& joint, int n) const {
  const int ns = static_cast<int>(speeds_.size());
  if (n <= 0 || joint.size() != static_cast<std::size_t>(ns) * static_cast<std::size_t>(n))
    throw std::invalid_argument("RouteFilter::predict: the joint belief has " +
                                std::to_string(joint.size()) + " entries, not speeds (" +
                                std::to_string(ns) + ") x positions (" + std::to_string(n) + ")");
  const double change = config_.speed_change_probability, jump = config_.jump_probability;
  double total = 0.0;
  for (double v : joint) total += v;
  // Speed changes first (to the neighbours in the order back, still, slowest .. fastest).
  std::vector<double> mixed(joint.size(), 0.0);
  for (int s = 0; s < ns; ++s) {
    const bool lo = s > 0, hi = s + 1 < ns;
    const double to_each = (lo && hi) ? 0.5 * change : change;
    for (int j = 0; j < n; ++j) {
      const double m = joint[static_cast<size_t>(s) * n + j];
      if (m == 0.0) continue;
      mixed[static_cast<size_t>(s) * n + j] += (1.0 - change) * m;
      if (lo) mixed[static_cast<size_t>(s - 1) * n + j] += to_each * m;
      if (hi) mixed[static_cast<size_t>(s + 1) * n + j] += to_each * m;
    }
  }
  // Stopping and starting: a moving query stands still, and a still one drives off at any forward
  // speed, in one query frame.
  const double stop = config_.stop_probability, start = config_.start_probability;
  if ((stop > 0.0 || start > 0.0) && ns > 2) {
    const double start_each = start / (ns - 2);
    for (int j = 0; j < n; ++j) {
      double moving = 0.0;
      for (int s = 2; s < ns; ++s) moving += mixed[static_cast<size_t>(s) * n + j];
      const double still = mixed[static_cast<size_t>(n) + j];
      if (moving == 0.0 && still == 0.0) continue;
      mixed[static_cast<size_t>(n) + j] = (1.0 - start) * still + stop * moving;
      for (int s = 2; s < ns; ++s) {
        double& m = mixed[static_cast<size_t>(s) * n + j];
        m = (1.0 - stop) * m + start_each * still;
      }
    }
  }
  // Then each speed moves its mass; a jump spreads a share over every frame and speed.
  std::vector<double> out(joint.size(), jump * total / (static_cast<double>(n) * ns));
  for (int s = 0; s < ns; ++s) {
    const double v = speeds_[s];
    for (int j = 0; j < n; ++j) {
      const double m = (1.0 - jump) * mixed[static_cast<size_t>(s) * n + j];
      if (m == 0.0) continue;
      const double to = std::clamp(j + v * config_.subframes, 0.0, static_cast<double>(n - 1));
      const int a = static_cast<int>(std::floor(to));
      const double frac = to - a;
      out[static_cast<size_t>(s) * n + a] += (1.0 - frac) * m;
      if (frac > 0.0) out[static_cast<size_t>(s) * n + a + 1] += frac * m;
    }
  }
  return out;
}

const std::vector<float>& RouteFilter::add(const std::vector<float>& distances) {
  if (distances.empty()) throw std::invalid_argument("RouteFilter::add: no reference");
  if (!posterior_.empty() && distances.size() != posterior_.size())
    throw std::invalid_argument("RouteFilter::add: " + std::to_string(distances.size()) +
                                " distances, the earlier queries had " +
                                std::to_string(posterior_.size()));
  for (float v : distances)
    if (!std::isfinite(v)) throw std::invalid_argument("RouteFilter::add: non-finite distance");
  const int frames = static_cast<int>(distances.size());
  const int k = config_.subframes;
  const int n = frames * k;  // grid positions: frame j holds positions j k .. j k + k - 1
  const int ns = static_cast<int>(speeds_.size());
  std::vector<float> d = config_.contrast_window_frames > 0
                             ? contrastEnhance(distances, config_.contrast_window_frames)
                             : distances;
  if (config_.hub_prior_queries > 0.0) {
    if (sum_.empty()) {
      sum_.assign(frames, 0.0);
      sum_sq_.assign(frames, 0.0);
    }
    const double w = config_.hub_prior_queries + static_cast<double>(queries_);
    for (int j = 0; j < frames; ++j) {
      const double mean = sum_[j] / w;
      const double var = std::max(1e-6, (sum_sq_[j] + config_.hub_prior_queries) / w - mean * mean);
      sum_[j] += d[j];
      sum_sq_[j] += static_cast<double>(d[j]) * d[j];
      d[j] = static_cast<float>((d[j] - mean) / std::sqrt(var));
    }
  }
  std::vector<double> joint;
  if (joint_.empty()) {
    joint.assign(static_cast<size_t>(ns) * n, 0.0);
    const double each = 1.0 / (static_cast<double>(n) * (ns - 2));
    std::fill(joint.begin() + 2 * static_cast<size_t>(n), joint.end(), each);
  } else {
    joint = predict(joint_, n);
  }
  // exp(-gain (d - min d)): the same likelihood up to a constant, never overflowing.
  const float d_min = *std::min_element(d.begin(), d.end());
  std::vector<double> like(n);
  for (int p = 0; p < n; ++p) {
    const int j = p / k;
    like[p] = std::exp(-config_.likelihood_gain * static_cast<double>(d[j] - d_min));
  }
  double total = 0.0;
  for (int s = 0; s < ns; ++s)
    for (int j = 0; j < n; ++j) total += joint[static_cast<size_t>(s) * n + j] *= like[j];
  if (!(total > 0.0) || !std::isfinite(total)) {
    // Everything underflowed (a belief far from a very sure observation): the observation alone.
    total = 0.0;
    for (int s = 2; s < ns; ++s)
      for (int j = 0; j < n; ++j) total += joint[static_cast<size_t>(s) * n + j] = like[j];
    for (int j = 0; j < n; ++j) joint[j] = joint[static_cast<size_t>(n) + j] = 0.0;
  }
  for (double& v : joint) v /= total;
  joint_ = std::move(joint);
  posterior_.assign(frames, 0.0);
  for (int s = 0; s < ns; ++s)
    for (int p = 0; p < n; ++p) posterior_[p / k] += joint_[static_cast<size_t>(s) * n + p];
  const int n_frames = frames;
  ++queries_;
  best_ = static_cast<int>(std::max_element(posterior_.begin(), posterior_.end()) -
                           posterior_.begin());
  const int r = config_.confidence_radius_frames;
  confidence_ = 0.0;
  for (int j = std::max(0, best_ - r); j <= std::min(n_frames - 1, best_ + r); ++j)
    confidence_ += posterior_[j];
  confidence_ = std::min(1.0, confidence_);
  scores_.resize(n_frames);
  for (int j = 0; j < n_frames; ++j) scores_[j] = static_cast<float>(-posterior_[j]);
  return scores_;
}

double RouteFilter::bestSpeed() const {
  if (best_ < 0) return 0.0;
  const int k = config_.subframes;
  const int n = static_cast<int>(posterior_.size()) * k;
  const int ns = static_cast<int>(speeds_.size());
  // The speed with the most mass in the best frame.
  std::vector<double> mass(ns, 0.0);
  for (int p = best_ * k; p < best_ * k + k; ++p)
    for (int s = 0; s < ns; ++s) mass[s] += joint_[static_cast<size_t>(s) * n + p];
  return speeds_[std::max_element(mass.begin(), mass.end()) - mass.begin()];
}

}  // namespace adaptive_perception::places
