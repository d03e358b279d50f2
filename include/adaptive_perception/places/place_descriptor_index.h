#pragma once
// The whole-image descriptors (global_descriptor.h) of every training image of a place database,
// with each image's place: node distances for a cue, the counterpart of PlaceIndex's eq. (5) for
// the colour histograms. A place's distance is that of its NEAREST training image (not the mean:
// a place's images show it from several headings, and one of them is the view being recognised),
// in the cue's z-score units over all training images (traversal_matcher.h, cueDistances),
// counted from the nearest image of all: the best place has distance 0, the others more, as eqs.
// (6)-(7) and the place filter expect of a distance.
#include <array>
#include <string>
#include <vector>

#include "adaptive_perception/places/traversal_matcher.h"

namespace adaptive_perception::places {

class PlaceDescriptorIndex {
 public:
  /// Places in the order of the PlaceIndex they go with (PlaceDatabase: name order).
  explicit PlaceDescriptorIndex(std::vector<std::string> place_names = {},
                                GlobalDescriptorConfig config = {});

  /// Adds one training image of place `place` (an index into the names). Throws
  /// std::invalid_argument on an unknown place or rows of other settings.
  void addImage(int place, const ImageDescriptors& d);
  int numPlaces() const { return static_cast<int>(names_.size()); }
  const std::vector<std::string>& placeNames() const { return names_; }
  int totalImages() const { return rows_.size(); }
  /// The place of the training image in row `row` (the order stored).
  int placeOfImage(int row) const { return place_.at(static_cast<size_t>(row)); }
  const GlobalDescriptorConfig& config() const { return rows_.config(); }

  /// Per place: the smallest cue distance of its training images to `query`, minus the smallest
  /// of all; +inf for a place without image. Throws std::invalid_argument when no image is
  /// stored.
  std::vector<double> nodeDistances(const std::array<double, kNumDescriptorKinds>& weights,
                                    const ImageDescriptors& query) const;
  /// The cue's distance of `query` to every training image, in the order stored (cueDistances).
  std::vector<float> imageDistances(const std::array<double, kNumDescriptorKinds>& weights,
                                    const ImageDescriptors& query) const;
  /// Node distances from per-image scores (totalImages() values, lower = better; e.g. a
  /// sequence matcher's): per place its best image's score minus the best of all.
  std::vector<double> nodeDistancesOf(const std::vector<float>& image_scores) const;

 private:
  std::vector<std::string> names_;
  ReferenceTraversal rows_;
  std::vector<int> place_;  // per row
};

}  // namespace adaptive_perception::places
