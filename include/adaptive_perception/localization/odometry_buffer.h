#pragma once
// Odometry poses kept by their stamps, so that the motion between two images is measured at the
// images' own times, not at whatever odometry message happened to arrive last. With the newest
// message instead, two replays of the same log could move a filter by different steps (odometry
// and images come on separate connections; which arrives first is chance).
//
// Guarantees:
// - `at(t_s)` is the newest pose stamped at or before t_s, or nothing when every pose kept is
//   newer, or when the newest at or before t_s is older than `max_age_s` (a stalled odometry
//   source is not taken as a robot standing still).
// - A pose older than the newest kept by more than `restart_after_back_s` means time went back (a
//   looped log): the poses kept are dropped and the new one is the first. One older by less (a
//   reordering network) is ignored. Equal stamps replace.
// - `dropAfter(t_s)` forgets the poses stamped after t_s (the caller's images jumped back).
// - At most `capacity` poses are kept; the oldest go first.
#include <cstddef>
#include <deque>
#include <optional>
#include <utility>

#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::localization {

struct OdometryBufferConfig {
  std::size_t capacity = 500;         // poses kept (10 s of a 50 Hz odometry)
  double max_age_s = 1.0;             // a pose older than this before the image is not used
  double restart_after_back_s = 1.0;  // a pose this much older than the newest starts again
};

class OdometryBuffer {
 public:
  explicit OdometryBuffer(OdometryBufferConfig config = {}) : config_(config) {}

  void add(double stamp_s, const math::SE2& pose) {
    if (!poses_.empty() && stamp_s < poses_.back().first) {
      if (poses_.back().first - stamp_s <= config_.restart_after_back_s) return;
      poses_.clear();
    }
    if (!poses_.empty() && stamp_s == poses_.back().first) poses_.pop_back();
    poses_.emplace_back(stamp_s, pose);
    while (poses_.size() > config_.capacity) poses_.pop_front();
  }

  std::optional<math::SE2> at(double stamp_s) const {
    for (auto it = poses_.rbegin(); it != poses_.rend(); ++it) {
      if (it->first > stamp_s) continue;
      if (stamp_s - it->first > config_.max_age_s) return std::nullopt;
      return it->second;
    }
    return std::nullopt;
  }

  void dropAfter(double stamp_s) {
    while (!poses_.empty() && poses_.back().first > stamp_s) poses_.pop_back();
  }
  void clear() { poses_.clear(); }
  std::size_t size() const { return poses_.size(); }

 private:
  OdometryBufferConfig config_;
  std::deque<std::pair<double, math::SE2>> poses_;
};

}  // namespace adaptive_perception::localization
