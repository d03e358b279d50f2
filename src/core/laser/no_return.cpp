#include "adaptive_perception/laser/no_return.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace adaptive_perception::laser {

namespace {
constexpr double kBinM = 0.01;           // the histogram's bin
constexpr double kMaxCountedM = 1000.0;  // readings beyond this are not binned (no laser reaches it)
}  // namespace

void NoReturnConfig::validate() const {
  if (min_count < 1) throw std::invalid_argument("NoReturnConfig: min_count must be >= 1");
  if (!(std::isfinite(gap_m) && gap_m > 0.0))
    throw std::invalid_argument("NoReturnConfig: gap_m must be > 0");
  if (!(std::isfinite(margin_m) && margin_m >= 0.0))
    throw std::invalid_argument("NoReturnConfig: margin_m must be >= 0");
}

NoReturnFinder::NoReturnFinder(NoReturnConfig config) : config_(config) { config_.validate(); }

void NoReturnFinder::add(const std::vector<float>& ranges_m, double range_max_m) {
  for (float r : ranges_m) {
    if (!std::isfinite(r) || r <= 0.0f || !(r < range_max_m) || r > kMaxCountedM) continue;
    if (r > max_) {
      max_ = r;
      at_max_ = 1;
    } else if (r == max_) {
      ++at_max_;
    }
    const size_t bin = static_cast<size_t>(r / kBinM);
    if (bin >= bins_.size()) bins_.resize(bin + 1, 0);
    ++bins_[bin];
  }
}

std::optional<double> NoReturnFinder::value() const {
  if (at_max_ < config_.min_count) return std::nullopt;
  // The readings in [max - gap, max), to the bin: those in max's own bin, less the ones at max.
  const double lo = std::max(0.0, static_cast<double>(max_) - config_.gap_m);
  long below = -at_max_;
  for (size_t b = static_cast<size_t>(lo / kBinM); b < bins_.size(); ++b) below += bins_[b];
  if (at_max_ <= below) return std::nullopt;
  return static_cast<double>(max_);
}

long NoReturnFinder::apply(std::vector<float>* ranges_m) const {
  const std::optional<double> v = value();
  if (!v) return 0;
  const double from = *v - config_.margin_m;
  long n = 0;
  for (float& r : *ranges_m)
    if (std::isfinite(r) && r >= from) {
      r = std::numeric_limits<float>::infinity();
      ++n;
    }
  return n;
}

long NoReturnFinder::mark(std::vector<float>* ranges_m, double range_max_m, bool* found_now) {
  const bool known = value().has_value();
  add(*ranges_m, range_max_m);
  *found_now = !known && value().has_value();
  return apply(ranges_m);
}

}  // namespace adaptive_perception::laser
