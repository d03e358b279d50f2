#pragma once
// Odometry poses kept by their stamps, so that the motion between two images is measured at the
// images' own times, not at whatever odometry message happened to arrive last. With the newest
// message instead, two replays of the same log could move a filter by different steps (odometry
// and images come on separate connections; which arrives first is chance). A caller that waits
// until `newest()` reaches an image's stamp before asking `at()` gets the same answer whatever
// the order of arrival.
//
// Guarantees:
// - `at(t_s)` is the pose at t_s, interpolated between the poses stamped on either side of it
//   (position linearly, heading along the shorter way); the newest pose when t_s is beyond it by
//   at most `max_age_s`; nothing when every pose kept is newer than t_s, or when the newest at or
//   before t_s is older than `max_age_s` with none after (a stalled odometry source is not taken
//   for a robot standing still).
// - Poses are kept in stamp order whatever order they come in; a stamp already kept is replaced.
//   A pose older than the newest by more than `restart_after_back_s` means time went back (a
//   looped log): the poses kept are dropped and it is the first.
// - `restartAt(t_s)`: the caller's images went back to t_s; when the newest pose is more than
//   `restart_after_back_s` after it, the poses are of the time before the jump and are dropped.
// - Poses older than the newest by more than `span_s` are dropped.
#include <cmath>
#include <iterator>
#include <map>
#include <optional>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::localization {

struct OdometryBufferConfig {
  double max_age_s = 1.0;             // an image this long after the newest pose gets none
  double restart_after_back_s = 1.0;  // a pose this much older than the newest starts again
  double span_s = 10.0;               // poses kept, back from the newest
};

class OdometryBuffer {
 public:
  explicit OdometryBuffer(OdometryBufferConfig config = {}) : config_(config) {}

  void add(double stamp_s, const math::SE2& pose) {
    if (const auto n = newest(); n && *n - stamp_s > config_.restart_after_back_s) poses_.clear();
    poses_[stamp_s] = pose;
    const double oldest_kept = poses_.rbegin()->first - config_.span_s;
    while (poses_.begin()->first < oldest_kept) poses_.erase(poses_.begin());
  }

  std::optional<math::SE2> at(double stamp_s) const {
    const auto after = poses_.lower_bound(stamp_s);  // first stamped at or after
    if (after != poses_.end() && after->first == stamp_s) return after->second;
    if (after == poses_.begin()) return std::nullopt;  // every pose is newer
    const auto before = std::prev(after);
    if (after == poses_.end()) {
      if (stamp_s - before->first > config_.max_age_s) return std::nullopt;
      return before->second;
    }
    const double s = (stamp_s - before->first) / (after->first - before->first);
    const math::SE2& a = before->second;
    const math::SE2& b = after->second;
    return math::SE2(a.x_m + s * (b.x_m - a.x_m), a.y_m + s * (b.y_m - a.y_m),
                     a.yaw_rad + s * math::wrapAngle(b.yaw_rad - a.yaw_rad));
  }

  std::optional<double> newest() const {
    if (poses_.empty()) return std::nullopt;
    return poses_.rbegin()->first;
  }
  void restartAt(double stamp_s) {
    if (const auto n = newest(); n && *n - stamp_s > config_.restart_after_back_s) poses_.clear();
  }
  void clear() { poses_.clear(); }
  std::size_t size() const { return poses_.size(); }
  const OdometryBufferConfig& config() const { return config_; }

 private:
  OdometryBufferConfig config_;
  std::map<double, math::SE2> poses_;
};

}  // namespace adaptive_perception::localization
