#pragma once
// Place recognition by histogram correlation (papers/004 sections 5-6): the node-averaged distance
// of a test image to each place's training images (eq. 5), the average over several test images
// (eq. 6, eqs. 8-10), the confidence as the fraction of test images agreeing (eq. 7), and the
// paper's choice of the colour space / method with the highest confidence.
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "adaptive_perception/places/histogram.h"
#include "adaptive_perception/places/histogram_distance.h"

namespace adaptive_perception::places {

/// The training images of every place, in memory: for each histogram space one contiguous
/// row-major matrix (one row of 3 * bins floats per image) and the place of each row, so that a
/// query streams through memory once.
class PlaceIndex {
 public:
  explicit PlaceIndex(int bins = 256) : bins_(bins) {}

  int bins() const { return bins_; }
  /// Adds a place (or returns the index of the one with that name).
  int addPlace(const std::string& name);
  int placeIndex(const std::string& name) const;  // -1 when unknown
  const std::vector<std::string>& placeNames() const { return names_; }
  int numPlaces() const { return static_cast<int>(names_.size()); }
  /// Adds one training image of `place` with the histograms it has; throws std::invalid_argument
  /// on a bin count other than bins() or an unknown place.
  void addImage(int place, const ImageHistograms& h);
  /// Training images of a place in `space`.
  int imageCount(int place, int space) const;
  int totalImages(int space) const { return static_cast<int>(rows_[space].place.size()); }
  bool hasSpace(int space) const { return !rows_[space].place.empty(); }

  /// eq. (5): for each place x, D_x = (1/n) sum over its n training images of d(H, K) / 3 (the
  /// band-averaged distance of histogramDistance). +inf for a place with no training image in
  /// `space`. Throws std::invalid_argument when `test` lacks `space`. Computed by HistogramQuery
  /// (single precision, SIMD), which agrees with histogramDistance to about 1e-6.
  std::vector<double> nodeDistances(int space, Distance d, const ImageHistograms& test) const;

 private:
  struct Rows {
    std::vector<float> data;  // totalImages x 3 * bins
    std::vector<int> place;
    std::vector<double> k_terms;  // per row: HistogramQuery::storedTerms
  };
  int bins_;
  std::vector<std::string> names_;
  std::array<Rows, kNumSpaces> rows_;
  std::array<std::vector<int>, kNumSpaces> counts_;  // per space, per place
};

/// The outcome of recognising one set of m test images with one space and method.
struct Recognition {
  int space = 0;  // -1: a whole-image cue (place_recognizer.h), no colour space
  Distance method = Distance::kChiSquare;
  int place = -1;                       // argmin of total_distances
  double confidence = 0.0;              // eq. (7): votes[place] / test_images
  std::vector<double> total_distances;  // eq. (6): mean over the test images of D_x
  std::vector<int> votes;               // test images whose own nearest place is x
  int test_images = 0;
  /// (second smallest - smallest) / second smallest total distance, in [0, 1]: 0 when two places
  /// tie. Breaks ties between equally confident choices.
  double margin = 0.0;
};

/// eqs. (6)-(7) from each test image's node distances (eq. 5). Throws std::invalid_argument on an
/// empty set or rows of different lengths.
Recognition combineTestImages(const std::vector<std::vector<double>>& node_distances, int space,
                              Distance method);

/// Recognition for every (space, method) pair, spaces in the outer loop. Spaces the index lacks
/// are skipped.
std::vector<Recognition> recognizeAll(const PlaceIndex& index,
                                      const std::vector<ImageHistograms>& test_images,
                                      const std::vector<int>& spaces,
                                      const std::vector<Distance>& methods);

/// Section 6: the choice with the highest confidence; ties go to the larger margin, then to the
/// earlier entry. Throws std::invalid_argument on an empty list.
const Recognition& mostConfident(const std::vector<Recognition>& candidates);

}  // namespace adaptive_perception::places
