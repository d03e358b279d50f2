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

std::vector<float> PlaceDescriptorIndex::imageDistances(
    const std::array<double, kNumDescriptorKinds>& weights, const ImageDescriptors& query) const {
  return cueDistances(rows_, query, weights);
}

std::vector<double> PlaceDescriptorIndex::nodeDistancesOf(
    const std::vector<float>& image_scores) const {
  if (image_scores.size() != place_.size())
    throw std::invalid_argument(
        "PlaceDescriptorIndex::nodeDistancesOf: " + std::to_string(image_scores.size()) +
        " scores for " + std::to_string(place_.size()) + " images");
  std::vector<double> out(names_.size(), std::numeric_limits<double>::infinity());
  if (image_scores.empty()) return out;
  const double lowest = *std::min_element(image_scores.begin(), image_scores.end());
  for (size_t r = 0; r < image_scores.size(); ++r)
    out[place_[r]] = std::min<double>(out[place_[r]], image_scores[r] - lowest);
  return out;
}

std::vector<double> PlaceDescriptorIndex::nodeDistances(
    const std::array<double, kNumDescriptorKinds>& weights, const ImageDescriptors& query) const {
  return nodeDistancesOf(imageDistances(weights, query));
}

}  // namespace adaptive_perception::places
