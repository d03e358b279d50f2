#pragma once
// A discrete Bayes filter over the places of a topological map: the paper's "future work"
// (papers/004 section 8), using adjacency and successive images instead of each image alone.
//
// Motion: between two images the robot stays with probability stay_probability, otherwise moves
// to one of the adjacent places (equally likely); a small teleport_probability spread over all
// places lets the filter recover from a wrong belief or a missing edge. A place with no
// neighbour keeps the moving mass.
//
// Observation: the node distances D_x of one image (eq. 5) become a likelihood that does not
// depend on the distance's scale: r_x = (D_x - D_min) / (D_median - D_min), L_x = exp(-sharpness
// * r_x). Places with no training image (D_x = inf) get likelihood 0 unless every place is inf.
#include <string>
#include <vector>

namespace adaptive_perception::places {

struct PlaceFilterConfig {
  double stay_probability = 0.8;       // per image
  double teleport_probability = 0.02;  // per image, spread over all places
  double likelihood_sharpness = 4.0;   // larger trusts single images more

  void validate() const;  // throws std::invalid_argument naming the bad field
};

class PlaceFilter {
 public:
  /// `adjacency[x]` lists the neighbours of place x (indices < number of places; symmetric edges
  /// are expected but not required). Starts uniform.
  PlaceFilter(std::vector<std::vector<int>> adjacency, PlaceFilterConfig config = {});

  int numPlaces() const { return static_cast<int>(belief_.size()); }
  void reset();  // uniform belief
  /// The motion step above.
  void predict();
  /// The observation step with one image's node distances (size numPlaces()). Throws
  /// std::invalid_argument on a size mismatch or a NaN.
  void update(const std::vector<double>& node_distances);
  /// Observation likelihood (unnormalised) used by update(): exposed for tests and plots.
  std::vector<double> likelihood(const std::vector<double>& node_distances) const;

  const std::vector<double>& belief() const { return belief_; }
  int best() const;  // the place of highest belief

 private:
  std::vector<std::vector<int>> adjacency_;
  PlaceFilterConfig config_;
  std::vector<double> belief_;
};

}  // namespace adaptive_perception::places
