#include "adaptive_perception/places/place_descriptor_index.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace adaptive_perception::places {

PlaceDescriptorIndex::PlaceDescriptorIndex(std::vector<std::string> place_names,
                                           GlobalDescriptorConfig config)
    : names_(std::move(place_names)), rows_(config) {}

void PlaceDescriptorIndex::addImage(int place, const ImageDescriptors& d) {
  if (place < 0 || place >= numPlaces())
    throw std::invalid_argument("PlaceDescriptorIndex::addImage: unknown place " +
                                std::to_string(place));
  rows_.add(d);
  place_.push_back(place);
}

std::vector<double> PlaceDescriptorIndex::nodeDistances(
    const std::array<double, kNumDescriptorKinds>& weights, const ImageDescriptors& query) const {
  const std::vector<float> d = cueDistances(rows_, query, weights);
  std::vector<double> out(names_.size(), std::numeric_limits<double>::infinity());
  const double lowest = *std::min_element(d.begin(), d.end());
  for (size_t r = 0; r < d.size(); ++r)
    out[place_[r]] = std::min<double>(out[place_[r]], d[r] - lowest);
  return out;
}

}  // namespace adaptive_perception::places
