#pragma once
// Place recognition along a route: a reference traversal (every stored image its own place, in
// the order it was driven) and an online matcher that answers, for each new query image, how well
// it matches each reference image.
//
// Methods (TraversalMatcherConfig::method):
//   thumbnail, gradient, chromaticity   one whole-image cue (global_descriptor.h) alone;
//   words      the bag of SIFT words (bag_of_words.h; the references' vocabulary, learnWords);
//   fused      the single-image cues combined: each cue's distances to the references turned into
//              z-scores over the references (so that cues of different scales add), then the
//              weighted mean with `fusion`'s weights (the words among them when fusion.words > 0);
//   sequence   SeqSLAM trajectory search (sequence_matcher.h) over the fused distances of the last
//              sequence.sequence_frames queries;
//   route      (default) the Bayes filter along the reference traversal (route_filter.h) observing
//              the fused distances; its scores are the negated posterior and its confidence the
//              posterior's mass around the best frame. It answers from the first query and
//              follows stops, speed changes, backing up and jumps, which a straight line cannot:
//              on Nordland it beats the sequence search at 8 of 9 speeds and drives
//              (docs/places_across_light.md).
// The fusion weights are settings chosen once on development data (docs/places_across_light.md
// gives the measurements), never from the images being recognised. Every method's scores are
// z-scores over the references (lower = better).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "adaptive_perception/places/bag_of_words.h"
#include "adaptive_perception/places/global_descriptor.h"
#include "adaptive_perception/places/route_filter.h"
#include "adaptive_perception/places/sequence_matcher.h"

namespace adaptive_perception::places {

struct TraversalMatcherConfig {
  GlobalDescriptorConfig descriptor;
  SequenceMatcherConfig sequence;
  RouteFilterConfig route;
  std::string method = "route";  // thumbnail, gradient, chromaticity, words, fused, sequence, route
  FusionWeights fusion;

  void validate() const;  // throws std::invalid_argument naming the bad field
  /// The method names above, for messages.
  static const char* methodNames();
};

/// The reference traversal: descriptors of every cue, one row per image, in traversal order.
class ReferenceTraversal {
 public:
  explicit ReferenceTraversal(GlobalDescriptorConfig config = {});
  /// Appends one image's descriptors (from computeDescriptors with the same config). Throws
  /// std::invalid_argument on rows of the wrong length.
  void add(const ImageDescriptors& d);
  /// Learns the bag of words from every reference's SIFT descriptors (one matrix per reference,
  /// in order; ImageDescriptors::sift). Throws std::invalid_argument on a count other than
  /// size() and as BagOfWords does.
  void learnWords(const std::vector<cv::Mat>& sift, const BagOfWordsConfig& config = {});
  /// The bag of words (null before learnWords).
  const BagOfWords* words() const { return words_.get(); }
  int size() const { return rows_[0].rows; }
  const cv::Mat& rows(DescriptorKind k) const { return rows_[static_cast<int>(k)]; }
  const GlobalDescriptorConfig& config() const { return config_; }

 private:
  GlobalDescriptorConfig config_;
  std::array<cv::Mat, kNumDescriptorKinds> rows_;
  std::shared_ptr<const BagOfWords> words_;
};

/// One query's distances to every stored image for a cue (cueWeights): each weighted
/// descriptor's mean absolute differences as z-scores over the stored images, then their weighted
/// mean. Throws std::invalid_argument when nothing is stored.
std::vector<float> cueDistances(const ReferenceTraversal& stored, const ImageDescriptors& query,
                                const std::array<double, kNumDescriptorKinds>& weights);

class TraversalMatcher {
 public:
  /// `references` must outlive the matcher and not change while it is used.
  TraversalMatcher(const ReferenceTraversal& references, TraversalMatcherConfig config = {});

  /// The next query image: its score against every reference (lower = better). Throws
  /// std::invalid_argument when the reference traversal is empty, or when the method uses the
  /// words and the references have none or the query no `sift` matrix.
  const std::vector<float>& add(const ImageDescriptors& query);
  /// The latest answer's confidence (higher = surer): the route filter's posterior mass, or for
  /// every other method how far the best score lies below the others (separation()).
  double confidence() const;
  /// Forgets the query history (sequence, route), e.g. when time jumped back.
  void reset();
  const TraversalMatcherConfig& config() const { return config_; }

 private:
  const ReferenceTraversal& refs_;
  TraversalMatcherConfig config_;
  SequenceMatcher sequence_;
  RouteFilter route_;
  std::vector<float> scores_;
};

}  // namespace adaptive_perception::places
