#include "adaptive_perception/localization/global_localization.h"

#include <algorithm>

#include "adaptive_perception/math/parallel_for.h"

namespace adaptive_perception::localization {

GlobalLocalization::GlobalLocalization(const GlobalLocalizationConfig& config) : config_(config) {
  config_.validate();
}

void GlobalLocalization::clearPool() {
  pool_.clear();
  pool_.shrink_to_fit();
  pool_ll_.clear();
  pool_ll_.shrink_to_fit();
  frames_ = 0;
  from_proposals_ = false;
  pixel_stride_ = 0;
}

void GlobalLocalization::start() {
  stop();
  searching_ = config_.pool_size > 0;
}

void GlobalLocalization::stop() {
  searching_ = false;
  confirming_ = false;
  clearPool();
}

GlobalLocalization::SearchStep GlobalLocalization::searchImage(
    PoseSearch* search, const math::SE2& odom_delta, const cv::Mat& yuv,
    const color::SwitchingColorFilter& lighting, const Eigen::Isometry3d& base_to_optical,
    std::uint64_t seed, int count, math::Rng& rng, const std::vector<math::SE2>& proposals) {
  const bool first = pool_.empty();
  if (first) {
    const bool goal =
        config_.goal_pool_share * config_.goal_pool_size >= 2 && proposals.size() >= 2;
    const std::size_t n =
        static_cast<std::size_t>(goal ? config_.goal_pool_size : config_.pool_size);
    pool_.resize(n);
    pool_ll_.assign(n, 0.0);
    search->fillUniform(&pool_, n, seed);
    const std::size_t share = static_cast<std::size_t>(config_.goal_pool_share * n) / 2 * 2;
    const std::size_t taken = goal ? std::min(share, proposals.size() / 2 * 2) : 0;
    std::copy_n(proposals.begin(), taken, pool_.begin());
    from_proposals_ = taken > 0;
    pixel_stride_ = from_proposals_ ? config_.goal_pixel_stride : 0;
  }
  const std::size_t n = pool_.size();
  SampledImage image = search->coarseImage(yuv, base_to_optical, pixel_stride_);
  search->score(&pool_, &pool_ll_, 0, !first, odom_delta, image, lighting, base_to_optical);
  ++frames_;
  search->pushWindow(odom_delta, std::move(image), lighting, base_to_optical, first);
  SearchStep step;
  step.committed = frames_ >= config_.search_frames;
  if (step.committed) search->refine(&pool_, &pool_ll_, 0, n, config_.refine_candidates, seed);
  for (std::size_t i : search->draw(pool_ll_, n, count, rng)) step.poses.push_back(pool_[i]);
  if (!step.committed) return step;
  searching_ = false;
  confirming_ = config_.confirm_frames > config_.search_frames && !from_proposals_;
  if (!confirming_) {
    search->clearWindow();
    clearPool();
  }
  return step;
}

std::optional<PoseContest> GlobalLocalization::confirmImage(
    PoseSearch* search, const math::SE2& odom_delta, const cv::Mat& yuv,
    const color::SwitchingColorFilter& lighting, const Eigen::Isometry3d& base_to_optical,
    const std::vector<math::SE2>& particle_poses) {
  SampledImage image = search->coarseImage(yuv, base_to_optical);
  search->score(&pool_, &pool_ll_, 0, true, odom_delta, image, lighting, base_to_optical);
  search->pushWindow(odom_delta, std::move(image), lighting, base_to_optical, false);
  if (++frames_ < config_.confirm_frames) return std::nullopt;
  // The particles' poses are scored over the same images as the pool (each moved back by the
  // odometry).
  confirming_ = false;
  PoseContest contest;
  contest.candidates = pool_.size();
  contest.poses = std::move(pool_);
  contest.log_likelihoods = std::move(pool_ll_);
  clearPool();
  contest.poses.resize(contest.candidates + particle_poses.size());
  contest.log_likelihoods.resize(contest.poses.size());
  math::parallelFor(particle_poses.size(), search->threads(), [&](std::size_t i) {
    contest.poses[contest.candidates + i] = particle_poses[i];
    contest.log_likelihoods[contest.candidates + i] =
        search->windowLogLikelihood(particle_poses[i]);
  });
  return contest;
}

}  // namespace adaptive_perception::localization
