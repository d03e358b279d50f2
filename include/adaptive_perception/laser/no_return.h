#pragma once
// A laser's "no return" value found from its readings, for a sensor whose stated range_max is
// wrong: a driver or a log that writes 50.00 m for "no return" under a range_max of 81.9 m would
// otherwise give walls 50 m away. The rule (the one carmen_to_bag applies to a whole log,
// io/carmen_log.h): the largest finite reading below range_max is the no-return value once at
// least min_count readings are exactly at it and more of them than in the gap_m below it (a real
// far wall spreads its returns; a no-return value is one number repeated). Readings from then on
// within margin_m of it are no returns (+inf, as REP 117 has it).
//
// NoReturnFinder is fed scan after scan (a live sensor); its evidence only grows, so once found a
// value stays until a larger reading outvotes it.
#include <optional>
#include <vector>

namespace adaptive_perception::laser {

struct NoReturnConfig {
  long min_count = 10;     // readings exactly at the largest value before it is taken, >= 1
  double gap_m = 1.0;      // ... and more of them than in this much below it, > 0
  double margin_m = 0.1;   // readings this close below the value are no returns too, >= 0
  void validate() const;   // throws std::invalid_argument naming the field
};

class NoReturnFinder {
 public:
  explicit NoReturnFinder(NoReturnConfig config = {});
  /// Counts the finite readings of one scan below range_max_m (those at or beyond it are no
  /// returns by the sensor's own word).
  void add(const std::vector<float>& ranges_m, double range_max_m);
  /// The no-return value, once the rule holds.
  std::optional<double> value() const;
  /// Sets every reading at or above value() - margin_m to +inf; returns how many. None before a
  /// value is found.
  long apply(std::vector<float>* ranges_m) const;
  /// add() then apply() on one scan, as a node does; *found_now: the value was found with it.
  long mark(std::vector<float>* ranges_m, double range_max_m, bool* found_now);
  long readingsAtValue() const { return at_max_; }

 private:
  NoReturnConfig config_;
  float max_ = 0.0f;  // the largest finite reading so far
  long at_max_ = 0;   // readings exactly at max_
  // Every reading so far, counted in kBinM bins, for the readings in the gap below max_.
  std::vector<long> bins_;
};

}  // namespace adaptive_perception::laser
