#pragma once
// Online place recognition over a stream of images: each image's node distances (eq. 5) in the
// configured colour spaces and methods, a sliding window of the last M images combined by eqs.
// (6)-(7), the most confident space / method when set to "auto" (papers/004 section 6), and the
// topological Bayes filter (place_filter.h) over the database's adjacency. Used by the
// histogram_place_recognizer node and evaluate_places.
#include <deque>
#include <string>
#include <vector>

#include "adaptive_perception/places/place_filter.h"
#include "adaptive_perception/places/place_matcher.h"

namespace adaptive_perception::places {

struct PlaceRecognizerConfig {
  std::string color_space = "auto";  // a space name (histogram.h) or "auto": all the database has
  std::string method = "auto";       // a distance name, or "auto": chi_square, jeffrey, ks
  int window = 5;                    // images combined by eqs. (6)-(7), 1..1000
  bool use_filter = true;            // run the Bayes filter
  PlaceFilterConfig filter;

  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct PlaceResult {
  Recognition recognition;     // of the window, in the chosen space / method
  int images = 0;              // in the window
  std::vector<double> belief;  // the filter's, per place (empty without filter)
  int filtered_place = -1;
};

class PlaceRecognizer {
 public:
  explicit PlaceRecognizer(PlaceRecognizerConfig config = {});

  /// Installs the training images and the adjacency (index order); clears the window and resets
  /// the filter. Throws std::invalid_argument when the configured space is not in the index.
  void setDatabase(PlaceIndex index, std::vector<std::vector<int>> adjacency);
  /// Spaces whose histograms add() needs.
  const std::vector<int>& spaces() const { return spaces_; }
  /// Adds one image and recognises the window. Throws std::logic_error when the database has no
  /// trained place, std::invalid_argument when `h` lacks a needed space.
  PlaceResult add(const ImageHistograms& h);
  /// Clears the window and resets the filter (time jumped back, robot kidnapped).
  void reset();
  const PlaceIndex& index() const { return index_; }
  const PlaceRecognizerConfig& config() const { return config_; }

 private:
  PlaceRecognizerConfig config_;
  PlaceIndex index_;
  std::vector<int> spaces_;
  std::vector<Distance> methods_;
  std::deque<std::vector<std::vector<double>>> window_;  // [image][combo][place]
  std::vector<std::vector<int>> adjacency_;
  std::vector<PlaceFilter> filter_;  // zero or one
  long seen_ = 0;                    // images since reset()
};

}  // namespace adaptive_perception::places
