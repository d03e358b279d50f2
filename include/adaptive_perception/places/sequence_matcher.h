#pragma once
// Sequence matching over an ordered reference traversal, SeqSLAM-style (Milford and Wyeth, "SeqSLAM:
// Visual route-based navigation for sunny summer days and stormy winter nights", ICRA 2012),
// online: each query image is added once, with its distances to every reference image, and the
// answer uses only that image and the ones before it (what a robot has seen).
//
// 1. Local contrast enhancement: each query's distance vector d_j over the references becomes
//    (d_j - mean) / std over the contrast_window_frames references centred on j, so that a
//    reference that is close to every query (a bland frame) stops winning everywhere.
// 2. Trajectory search: the score of reference j for the latest query t is the minimum over
//    velocities v (velocity_steps values spread evenly in log v over [min_velocity, max_velocity]
//    reference frames per query frame) of the mean enhanced difference along the line through (t, j)
//    backwards: (1/L) sum_{k=0}^{L-1} D'[t - k][j - round(v k)], L = min(sequence_frames, queries
//    so far). A term that falls before the first reference counts as 0, the enhanced value of
//    chance, so a trajectory cut short by the traversal's start is less sure, not more.
//
// A query costs O(N) for the enhancement and O(L * velocity_steps * N) for the search (N
// references); the last L enhanced vectors are kept, nothing is recomputed over the history.
#include <deque>
#include <vector>

namespace adaptive_perception::places {

struct SequenceMatcherConfig {
  // Defaults: 20 query frames, any speed from half to twice the reference's in steps of 5%
  // (29 velocities), so that a query driven at another speed than the reference still lies on a
  // searched line: with the first setting (10 frames, 0.8-1.25x in 5 steps) Nordland at the
  // same speed gave recall@1 0.83 but at twice the speed 0.001 (docs/places_across_light.md).
  // A step of 5% keeps a line's end within half a frame of the true path over 20 frames.
  int sequence_frames = 20;       // L: query frames on one trajectory, 1..1000
  double min_velocity = 0.5;      // reference frames per query frame, > 0
  double max_velocity = 2.0;      // >= min_velocity
  int velocity_steps = 29;        // 1..100 (1: min_velocity only)
  int contrast_window_frames = 10;  // references in the enhancement window, >= 2

  void validate() const;  // throws std::invalid_argument naming the bad field
};

/// Step 1: each distance as a z-score over the `window_frames` references centred on it (the
/// window kept inside the traversal). A window of equal distances gives 0.
std::vector<float> contrastEnhance(const std::vector<float>& distances, int window_frames);

class SequenceMatcher {
 public:
  explicit SequenceMatcher(SequenceMatcherConfig config = {});

  /// Starts over (time jumped back, a new traversal).
  void reset();
  /// Adds the next query's distances to the N references (N fixed from the first call) and
  /// returns the sequence score of every reference (lower = better match; in units of the
  /// enhanced differences, about -2 for a clear match, 0 for chance). Throws
  /// std::invalid_argument on an empty vector, a changed N or a non-finite distance.
  const std::vector<float>& add(const std::vector<float>& distances);
  /// Queries since reset() (capped at nothing; the history used is the last sequence_frames).
  long queries() const { return queries_; }
  const SequenceMatcherConfig& config() const { return config_; }

  /// Step 1 alone, exposed for tests: the enhanced vector of one distance vector.
  std::vector<float> enhance(const std::vector<float>& distances) const;

 private:
  SequenceMatcherConfig config_;
  std::deque<std::vector<float>> history_;  // enhanced, newest first
  std::vector<float> scores_;
  std::vector<float> sum_;  // per reference, one velocity (scratch)
  long queries_ = 0;
};

}  // namespace adaptive_perception::places
