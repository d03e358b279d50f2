#pragma once
// Online place recognition over a stream of images: each image's node distances, a sliding
// window of the last M images combined by eqs. (6)-(7), and the topological Bayes filter
// (place_filter.h) over the database's adjacency. Used by the histogram_place_recognizer node and
// evaluate_places.
//
// The node distances come from the configured cue: "fused" (default), "thumbnail", "gradient" or
// "chromaticity", the whole-image cues of global_descriptor.h against each place's nearest
// training image (place_descriptor_index.h), which hold across a change of light; or "histogram",
// the paper's colour histograms (eq. 5) in color_space / method, with the most confident space /
// method when those are "auto" (papers/004 section 6). With the whole-image cues the filter also
// takes the sequence matcher's view of the last images (use_sequence); its answer is the fused
// one. When the database is one drive (a reference traversal: each place one training image, each
// image's place joined to the one stored before it), the route filter (route_filter.h) over its
// images gives the answer instead (use_route): the posterior's best frame and its mass.
#include <deque>
#include <string>
#include <vector>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/places/place_descriptor_index.h"
#include "adaptive_perception/places/place_filter.h"
#include "adaptive_perception/places/place_matcher.h"
#include "adaptive_perception/places/route_filter.h"
#include "adaptive_perception/places/sequence_matcher.h"

namespace adaptive_perception::places {

struct PlaceRecognizerConfig {
  std::string cue = "fused";  // fused, thumbnail, gradient, chromaticity, or histogram
  FusionWeights fusion;       // the fused cue's weights
  // cue "histogram" only:
  std::string color_space = "auto";  // a space name (histogram.h) or "auto": all the database has
  std::string method = "auto";       // a distance name, or "auto": chi_square, jeffrey, ks
  int window = 5;                    // images combined by eqs. (6)-(7), 1..1000
  bool use_filter = true;            // run the Bayes filter
  PlaceFilterConfig filter;
  // Whole-image cues with the filter on: SeqSLAM (sequence_matcher.h) over the training images in
  // the order they were stored, each place scored by its best image, as a second observation of
  // the filter beside the single image's. Off: it needs training images that are one continuous
  // drive at about the query's pace (a reference traversal); over the paper's sparse training
  // images (15 per place) it made the filter worse on every simulated train / test lighting pair
  // (omni: 0.84-0.96 -> 0.54-0.76; docs/places_across_light.md).
  bool use_sequence = false;
  SequenceMatcherConfig sequence;
  // Whole-image cues with the filter on, over a database that is one drive: the route filter
  // answers. On: it follows a stop, a change of speed and a kidnap where the topological filter
  // over single places cannot tell speed (route_filter_test; docs/places_across_light.md).
  bool use_route = true;
  RouteFilterConfig route;

  /// The numbers and switches histogram_place_recognizer sets (config/fields.h); the names
  /// (cue, color_space, method) aside.
  static const config::Fields<PlaceRecognizerConfig>& fields();
  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct PlaceResult {
  std::string cue;                   // the configured cue
  Recognition recognition;           // of the window (histogram cue: in the chosen space / method)
  int images = 0;                    // in the window
  std::vector<double> belief;        // the filter's, per place (empty without filter)
  int filtered_place = -1;           // the fused answer: the filter's most probable place
  double filtered_confidence = 0.0;  // its belief
  int sequence_place = -1;           // the sequence matcher's best place (-1 when it does not run)
  int route_frame = -1;              // the route filter's best training image (the order stored;
                                     // -1 when it does not run); its place is filtered_place
};

class PlaceRecognizer {
 public:
  explicit PlaceRecognizer(PlaceRecognizerConfig config = {});

  /// Installs the training images and the adjacency (index order); clears the window and resets
  /// the filter. Throws std::invalid_argument when the configured space is not in the index, or
  /// when a whole-image cue is configured and `descriptors` lacks images the index has (a
  /// database stored before the cues existed: train it again, or use the histogram cue).
  void setDatabase(PlaceIndex index, std::vector<std::vector<int>> adjacency,
                   PlaceDescriptorIndex descriptors = PlaceDescriptorIndex());
  /// True when the configured cue needs each image's whole-image descriptors in add().
  bool usesDescriptors() const { return config_.cue != "histogram"; }
  /// Spaces whose histograms add() needs.
  const std::vector<int>& spaces() const { return spaces_; }
  /// Adds one image and recognises the window. Throws std::logic_error when the database has no
  /// trained place, std::invalid_argument when `h` lacks a needed space or a whole-image cue is
  /// configured and `d` is null.
  PlaceResult add(const ImageHistograms& h, const ImageDescriptors* d = nullptr);
  /// Clears the window and resets the filter (time jumped back, robot kidnapped).
  void reset();
  /// True when the route filter answers: whole-image cues, use_filter and use_route on, and the
  /// database one drive (each place one image, each image's place adjacent to the one before).
  bool usesRoute() const { return !route_.empty(); }
  const PlaceIndex& index() const { return index_; }
  const PlaceRecognizerConfig& config() const { return config_; }

 private:
  bool isOneDrive() const;
  PlaceRecognizerConfig config_;
  PlaceIndex index_;
  PlaceDescriptorIndex descriptors_;
  std::vector<int> spaces_;
  std::vector<Distance> methods_;
  std::deque<std::vector<std::vector<double>>> window_;  // [image][combo][place]
  std::vector<std::vector<int>> adjacency_;
  std::vector<PlaceFilter> filter_;        // zero or one
  std::vector<SequenceMatcher> sequence_;  // zero or one
  std::vector<RouteFilter> route_;         // zero or one
  long seen_ = 0;                          // images since reset()
};

}  // namespace adaptive_perception::places
