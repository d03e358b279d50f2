#pragma once
// Localization along a reference traversal: a Bayes filter (a hidden Markov model) whose state is
// the reference frame the query is at and the speed it moves at, in reference frames per query
// frame (papers/004 section 8's filter over places, here over the frames of one drive).
//
// Speeds: `speed_steps` forward speeds spread evenly in log speed over [min_speed, max_speed] (the
// sequence matcher's range), then standing still (0) and going back (-1). Ordered back, still,
// slowest .. fastest, a speed keeps itself from one query frame to the next or, with
// speed_change_probability, becomes one of its neighbours in that order (half each; at either
// end the whole): the query slows down, stops, reverses or speeds up a step at a time. With
// stop_probability a moving query stands still at once, with start_probability a still one
// drives off at any forward speed. With
// jump_probability it jumps to any frame at any speed (a kidnap, a stretch the reference never
// saw). The first query's speed prior is the forward speeds' alone, equally.
//
// Motion: positions are kept at 1/subframes of a reference frame (frame j holds the positions
// j .. j + 1 - 1/subframes); a position's mass moves by its
// speed, a move between two grid positions splits the mass between them (linear interpolation),
// a move past either end of the traversal stays at that end. The finer grid keeps a speed that is
// not a whole number of frames from smearing the belief (with whole frames, a speed of 0.5 splits
// every frame's mass in two, and over 20 queries the belief spreads over +-2 frames).
//
// Observation: one query's distances to every reference (any cue, lower = closer; the matchers
// give z-scores over the references), optionally contrast-enhanced over contrast_window_frames
// references (contrastEnhance, as the sequence matcher does), then each reference's distance as a
// z-score over the queries so far (its running mean and deviation, starting from 0 and 1 with the
// weight of hub_prior_queries queries): a reference close to every query (a bland frame, a
// "hub") stops attracting the belief, and a stopped query parked on it no longer looks like
// evidence. The likelihood of every speed at
// frame j (each of its positions) is exp(-likelihood_gain * d_j).
//
// Guarantees: the posterior over frames sums to 1 after every add() (no NaN, nothing below 0); the
// first query's answer is the single-image one (the prior over frames is uniform); the answer uses
// only the queries so far (filtering, no smoothing); a query costs O(N subframes (speed_steps + 2)) after
// the distances, N references.
#include <vector>

namespace adaptive_perception::places {

struct RouteFilterConfig {
  double min_speed = 0.5;  // slowest forward speed, reference frames per query frame, (0, 100]
  double max_speed = 2.0;  // fastest, [min_speed, 100]
  // Forward speeds, log-spaced; 1..50 (1: min_speed alone). 9 over 0.5..2 are 1.19 times apart: a
  // query between two of them drifts from the belief's speed by at most 9% of a frame a frame (5,
  // 1.41 apart: 18%), and on Nordland at 0.6-2x the reference's speed recall@1 rose 0.800-0.927 ->
  // 0.844-0.929, while standing still lost a little to the slow speeds (docs/places_across_light.md).
  int speed_steps = 9;
  double speed_change_probability = 0.1;  // per query frame, to a neighbouring speed
  // Per query frame: a moving query stands still (whatever its speed), and a still one drives off
  // at any forward speed (equally). Without them a stop is reached one speed at a time, five steps
  // down from the reference's speed, and the speed never jumps. A stop is rare (0.003) and lasts
  // about five frames unless the images hold it longer (0.2). On Nordland a larger start
  // probability gains more (0.4-0.8: +0.02-0.03 at 0.6x and 1x), but lets go of a stop the images
  // hold weakly (route_filter_test's stops: 0.35 of the stopped frames at 0.5, 0.48 without stops,
  // 0.52 at 0.2; docs/places_across_light.md).
  double stop_probability = 0.003;
  double start_probability = 0.2;
  double jump_probability = 0.001;        // per query frame, to any frame and speed
  double likelihood_gain = 1.0;           // > 0
  int contrast_window_frames = 0;         // 0: the distances as they are; else >= 2
  int confidence_radius_frames = 2;       // confidence: the posterior within +-this of the best
  int subframes = 4;                      // positions per reference frame, 1..16
  double hub_prior_queries = 10.0;        // weight of the prior 0 / 1 of each reference's stats; 0: off

  void validate() const;  // throws std::invalid_argument naming the bad field
};

class RouteFilter {
 public:
  explicit RouteFilter(RouteFilterConfig config = {});

  /// Starts over (a new traversal, time jumped back).
  void reset();
  /// Adds the next query's distances to the N references (N fixed from the first call) and
  /// returns the negated posterior of every reference (lower = better, as every matcher's
  /// scores). Throws std::invalid_argument on an empty vector, a changed N or a non-finite
  /// distance; the filter is then unchanged.
  const std::vector<float>& add(const std::vector<float>& distances);

  /// The posterior over reference frames (speeds summed out).
  const std::vector<double>& posterior() const { return posterior_; }
  int best() const { return best_; }  // -1 before the first query
  /// The posterior mass within confidence_radius_frames of best(): 0..1.
  double confidence() const { return confidence_; }
  /// The most probable speed at best(), reference frames per query frame.
  double bestSpeed() const;
  long queries() const { return queries_; }
  const RouteFilterConfig& config() const { return config_; }
  /// The speeds of the state, in their order: -1, 0, then the forward ones slowest first.
  const std::vector<double>& speeds() const { return speeds_; }

  /// The motion step alone (exposed for tests): `joint[s * P + p]` is the mass at grid position p
  /// (in frame p / subframes) moving at speeds()[s], P positions; returns the joint belief one query
  /// frame later. Throws std::invalid_argument when joint is not speeds() x positions long.
  std::vector<double> predict(const std::vector<double>& joint, int positions) const;

 private:
  RouteFilterConfig config_;
  std::vector<double> speeds_;
  std::vector<double> joint_;  // speeds x grid positions
  std::vector<double> sum_, sum_sq_;  // per reference, over the queries so far
  std::vector<double> posterior_;
  std::vector<float> scores_;
  int best_ = -1;
  double confidence_ = 0.0;
  long queries_ = 0;
};

}  // namespace adaptive_perception::places
