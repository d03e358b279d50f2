#pragma once
// Odometry poses kept by their stamps, so that the motion between two images is measured at the
// images' own times, not at whatever odometry message happened to arrive last. With the newest
// message instead, two replays of the same log could move a filter by different steps (odometry
// and images come on separate connections; which arrives first is chance).
//
// OdometryBuffer guarantees:
// - `at(t_s)` is the pose at t_s, interpolated between the poses stamped on either side of it
//   (position linearly, heading along the shorter way) when they are at most `max_age_s` apart;
//   the newest pose when t_s is beyond it by at most `max_age_s`; otherwise nothing (every pose
//   newer, or a gap: a stalled odometry source is not taken for a robot standing still).
// - Poses are kept in stamp order whatever order they come in; a stamp already kept is replaced.
//   A pose older than the newest by more than `restart_after_back_s` means time went back (a
//   looped log): the poses kept are dropped and it is the first.
// - `restartAt(t_s)`: the caller's images went back to t_s; when the newest pose is more than
//   `restart_after_back_s` after it, the poses are of the time before the jump and are dropped.
// - Poses older than the newest by more than `span_s` are dropped.
//
// OdometrySync<Item> holds each image (any Item) until the odometry reaches its stamp, so that
// what a filter is given does not depend on the order the two streams arrive in:
// - `image(t, item)` and `odometry(t, pose)` return the images to process now, oldest first, each
//   with the pose at its stamp (or none): an image is released when odometry stamped at or after
//   it arrives, or, without it, when the next image comes (then counted in `unmatched()`).
// - After `max_unmatched` images in a row went without, images are released at once (no
//   odometry, or stamped on another clock) until the odometry reaches an image's stamp again.
// - `restart(t)` drops the held image (time went back) and the odometry of before the jump.
#include <cmath>
#include <iterator>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::localization {

struct OdometryBufferConfig {
  double max_age_s = 1.0;             // the widest gap bridged, and the oldest pose taken
  double restart_after_back_s = 1.0;  // a pose this much older than the newest starts again
  double span_s = 10.0;               // poses kept, back from the newest
};

class OdometryBuffer {
 public:
  explicit OdometryBuffer(OdometryBufferConfig config = {}) : config_(config) {}

  void add(double stamp_s, const math::SE2& pose) {
    restartAt(stamp_s);
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
    if (after->first - before->first > config_.max_age_s) return std::nullopt;
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
  std::size_t size() const { return poses_.size(); }
  const OdometryBufferConfig& config() const { return config_; }

 private:
  OdometryBufferConfig config_;
  std::map<double, math::SE2> poses_;
};

template <class Item>
class OdometrySync {
 public:
  struct Release {
    double stamp_s;
    Item item;
    std::optional<math::SE2> pose;  // the odometry at the stamp, or none
  };

  explicit OdometrySync(OdometryBufferConfig config = {}, int max_unmatched = 3)
      : odom_(config), max_unmatched_(max_unmatched) {}

  std::vector<Release> image(double stamp_s, Item item) {
    std::vector<Release> out;
    last_image_s_ = stamp_s;
    if (held_) {  // the odometry did not reach the held image before this one came
      ++unmatched_in_a_row_;
      ++unmatched_;
      out.push_back(take());
    }
    if (reaches(stamp_s)) {
      unmatched_in_a_row_ = 0;
    } else if (unmatched_in_a_row_ < max_unmatched_) {
      held_ = Release{stamp_s, std::move(item), std::nullopt};
      return out;
    } else {
      ++unmatched_;
    }
    out.push_back(Release{stamp_s, std::move(item), odom_.at(stamp_s)});
    return out;
  }

  std::vector<Release> odometry(double stamp_s, const math::SE2& pose) {
    odom_.add(stamp_s, pose);
    std::vector<Release> out;
    if (last_image_s_ && reaches(*last_image_s_)) unmatched_in_a_row_ = 0;
    if (held_ && reaches(held_->stamp_s)) out.push_back(take());
    return out;
  }

  void restart(double stamp_s) {
    held_.reset();
    unmatched_in_a_row_ = 0;
    odom_.restartAt(stamp_s);
  }

  bool waiting() const { return held_.has_value(); }
  long unmatched() const { return unmatched_; }
  bool matching() const { return unmatched_in_a_row_ < max_unmatched_; }

 private:
  bool reaches(double stamp_s) const { return odom_.newest() && *odom_.newest() >= stamp_s; }
  Release take() {
    Release r = std::move(*held_);
    held_.reset();
    r.pose = odom_.at(r.stamp_s);
    return r;
  }

  OdometryBuffer odom_;
  int max_unmatched_;
  std::optional<Release> held_;
  std::optional<double> last_image_s_;
  int unmatched_in_a_row_ = 0;
  long unmatched_ = 0;
};

}  // namespace adaptive_perception::localization
