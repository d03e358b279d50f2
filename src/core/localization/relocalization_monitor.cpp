#include "adaptive_perception/localization/relocalization_monitor.h"

#include <algorithm>
#include <cmath>

namespace adaptive_perception::localization {

RelocalizationMonitor::RelocalizationMonitor(const RelocalizationConfig& config) : config_(config) {
  config_.validate();
}

void RelocalizationMonitor::reset() {
  contest_ = PoseContest();
  frames_ = 0;
  seconds_since_check_ = 0.0;
}

std::optional<PoseContest> RelocalizationMonitor::observe(
    PoseSearch* search, const math::SE2& odom_delta, double dt_s, const cv::Mat& yuv,
    const color::SwitchingColorFilter& lighting, const Eigen::Isometry3d& base_to_optical,
    std::uint64_t seed, int frames, const std::vector<math::SE2>& particle_poses,
    const std::function<std::vector<math::SE2>()>& propose) {
  if (config_.interval_s <= 0.0) return std::nullopt;
  const bool starting = frames_ == 0;
  if (starting) {
    seconds_since_check_ += std::max(dt_s, 0.0);
    if (seconds_since_check_ < config_.interval_s) return std::nullopt;
  }
  SampledImage image = search->coarseImage(yuv, base_to_optical);
  if (starting) {
    // The particles have this image's motion already; the pool is drawn for it: uniform, its
    // first poses (whole mirrored pairs, at most the pool) replaced by the proposals.
    const std::vector<math::SE2> proposals = propose ? propose() : std::vector<math::SE2>();
    contest_.candidates = static_cast<std::size_t>(config_.pool_size);
    contest_.poses.resize(contest_.candidates + particle_poses.size());
    contest_.log_likelihoods.assign(contest_.poses.size(), 0.0);
    search->fillUniform(&contest_.poses, contest_.candidates, seed ^ 0x2545F4914F6CDD1Dull);
    proposed_ = std::min(contest_.candidates, proposals.size()) / 2 * 2;
    std::copy_n(proposals.begin(), proposed_, contest_.poses.begin());
    std::copy(particle_poses.begin(), particle_poses.end(),
              contest_.poses.begin() + static_cast<std::ptrdiff_t>(contest_.candidates));
  }
  search->score(&contest_.poses, &contest_.log_likelihoods, 0, !starting, odom_delta, image,
                lighting, base_to_optical);
  search->pushWindow(odom_delta, std::move(image), lighting, base_to_optical, starting);
  if (++frames_ < frames) return std::nullopt;
  PoseContest done = std::move(contest_);
  reset();
  return done;
}

}  // namespace adaptive_perception::localization
