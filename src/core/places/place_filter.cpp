#include "adaptive_perception/places/place_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace adaptive_perception::places {

void PlaceFilterConfig::validate() const {
  if (!(stay_probability >= 0.0 && stay_probability <= 1.0))
    throw std::invalid_argument("stay_probability must be in [0, 1]");
  if (!(teleport_probability >= 0.0 && teleport_probability <= 1.0 - stay_probability))
    throw std::invalid_argument("teleport_probability must be in [0, 1 - stay_probability]");
  if (!(likelihood_sharpness > 0.0 && std::isfinite(likelihood_sharpness)))
    throw std::invalid_argument("likelihood_sharpness must be positive");
}

PlaceFilter::PlaceFilter(std::vector<std::vector<int>> adjacency, PlaceFilterConfig config)
    : adjacency_(std::move(adjacency)), config_(config) {
  config_.validate();
  if (adjacency_.empty()) throw std::invalid_argument("PlaceFilter: no place");
  const int n = static_cast<int>(adjacency_.size());
  for (int x = 0; x < n; ++x)
    for (int y : adjacency_[x])
      if (y < 0 || y >= n || y == x)
        throw std::invalid_argument("PlaceFilter: place " + std::to_string(x) +
                                    " has a bad neighbour " + std::to_string(y));
  reset();
}

void PlaceFilter::reset() { belief_.assign(adjacency_.size(), 1.0 / adjacency_.size()); }

void PlaceFilter::predict() {
  const size_t n = belief_.size();
  const double move = 1.0 - config_.stay_probability - config_.teleport_probability;
  std::vector<double> next(n, config_.teleport_probability / n);
  for (size_t x = 0; x < n; ++x) {
    const double b = belief_[x];
    if (adjacency_[x].empty()) {
      next[x] += b * (config_.stay_probability + move);
      continue;
    }
    next[x] += b * config_.stay_probability;
    const double share = b * move / adjacency_[x].size();
    for (int y : adjacency_[x]) next[y] += share;
  }
  belief_ = std::move(next);
}

std::vector<double> PlaceFilter::likelihood(const std::vector<double>& d) const {
  if (d.size() != belief_.size())
    throw std::invalid_argument("PlaceFilter: " + std::to_string(d.size()) +
                                " node distances for " + std::to_string(belief_.size()) +
                                " places");
  std::vector<double> finite;
  for (double v : d) {
    if (std::isnan(v)) throw std::invalid_argument("PlaceFilter: NaN node distance");
    if (std::isfinite(v)) finite.push_back(v);
  }
  std::vector<double> l(d.size(), finite.empty() ? 1.0 : 0.0);
  if (finite.empty()) return l;
  std::sort(finite.begin(), finite.end());
  const double lo = finite.front();
  const double med = finite[finite.size() / 2];
  const double scale = med - lo;
  for (size_t x = 0; x < d.size(); ++x) {
    if (!std::isfinite(d[x])) continue;
    l[x] = scale > 0.0 ? std::exp(-config_.likelihood_sharpness * (d[x] - lo) / scale) : 1.0;
  }
  return l;
}

void PlaceFilter::update(const std::vector<double>& node_distances) {
  const std::vector<double> l = likelihood(node_distances);
  double sum = 0.0;
  for (size_t x = 0; x < l.size(); ++x) sum += (belief_[x] *= l[x]);
  if (sum <= 0.0 || !std::isfinite(sum)) {
    // The image rules out every place the belief held: restart from the image alone.
    double ls = 0.0;
    for (double v : l) ls += v;
    for (size_t x = 0; x < l.size(); ++x) belief_[x] = l[x] / ls;
    return;
  }
  for (double& b : belief_) b /= sum;
}

int PlaceFilter::best() const {
  return static_cast<int>(std::max_element(belief_.begin(), belief_.end()) - belief_.begin());
}

}  // namespace adaptive_perception::places
