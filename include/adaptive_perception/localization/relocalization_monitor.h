#pragma once
// The relocalization check of the RBPF: are the particles lost? It recovers from a kidnap, and from
// a global search that committed to the wrong place.
//
// Every interval_s seconds after the particles have committed, a pool of pool_size poses drawn as
// the global search's is (uniform, in point-mirrored pairs, the first of them replaced by the
// caller's proposals: poses around a goal in view) and the particles' own poses are scored side
// by side over the next GlobalLocalizationConfig::search_frames images, as the global search
// scores its pool (the search's coarse grid, each pose moved by the odometry, log-likelihoods
// summed), all under the priors' lighting; the refine_candidates best poses of both sides are
// refined alike. If the pool's best pose beats the best particle pose by more than `margin`
// (tempered log-likelihood summed over those images), the particles are lost: by default
// (`restart`) the global search starts again, with its full pool and its second draw; with
// restart false, `fraction` of the particles are drawn from the check's poses instead and the
// rest are kept.
//
// Why a likelihood ratio against the rest of the field and not the likelihood's level: the level
// swings with what the camera sees and with the light, and falls as far when the head turns to a
// bare stretch of carpet as after a kidnap. Why the priors' lighting and not the particles' own:
// after a kidnap the particles have learnt the colours under the wrong place's labels, and their
// lighting favours their own hypothesis. The check only has to tell that something beats the
// particles, not where the robot is, so it is small but frequent (the measured choices of
// interval, pool and candidates: docs/nodes/rbpf_localizer.md).
//
// Contract: the class holds the check's pool and timer and returns the finished contest; the
// caller settles it (PoseSearch::settle) and applies the decision.
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "adaptive_perception/localization/pose_search.h"

namespace adaptive_perception::localization {

struct RelocalizationConfig {
  double interval_s = 1.0;  // 0 turns the check off
  int pool_size = 2000;
  double margin = 2.0;    // tempered log-likelihood summed over the check's images
  double fraction = 0.5;  // of the particles redrawn from the check's poses (restart false)
  bool restart = true;
  int refine_candidates = 20;  // a side
  /// Its parameters' names, ranges and docs; defined in rbpf_configs.cpp.
  static const config::Fields<RelocalizationConfig>& fields();
  void validate() const { fields().validate(*this); }
};

class RelocalizationMonitor {
 public:
  explicit RelocalizationMonitor(const RelocalizationConfig& config);

  /// Forgets a running check and restarts the interval (the particles were placed anew).
  void reset();
  /// One image after the particles were weighed (and carry this image's motion): on the check's
  /// `frames`-th image, the contest of its pool against `particle_poses`, not yet
  /// settled. The particles' poses are taken when a check starts, and so is its pool: pool_size
  /// uniform poses, the first of them replaced by what `propose()` gives (called then only, when
  /// given; whole mirrored pairs, at most the pool).
  std::optional<PoseContest> observe(
      PoseSearch* search, const math::SE2& odom_delta, double dt_s, const cv::Mat& yuv,
      const color::SwitchingColorFilter& lighting, const Eigen::Isometry3d& base_to_optical,
      std::uint64_t seed, int frames, const std::vector<math::SE2>& particle_poses,
      const std::function<std::vector<math::SE2>()>& propose = {});

  const RelocalizationConfig& config() const { return config_; }
  /// The proposals in the pool of the check running or last started (0: all uniform).
  std::size_t proposed() const { return proposed_; }

 private:
  RelocalizationConfig config_;
  PoseContest contest_;               // the running check's poses
  int frames_ = 0;                    // images scored in the running check (0: none running)
  std::size_t proposed_ = 0;          // see proposed()
  double seconds_since_check_ = 0.0;  // since the particles were placed or the last check ended
};

}  // namespace adaptive_perception::localization
