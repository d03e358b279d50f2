#include "adaptive_perception/localization/pose_search.h"

#include <algorithm>

#include "adaptive_perception/math/parallel_for.h"
#include "adaptive_perception/math/particle_set.h"

namespace adaptive_perception::localization {

PoseSearch::PoseSearch(std::shared_ptr<const ImageLikelihood> likelihood,
                       const PoseSearchConfig& config, int threads)
    : likelihood_(std::move(likelihood)), config_(config), threads_(threads) {
  config_.validate();
}

math::SE2 PoseSearch::uniformPose(math::Rng& rng) const {
  const world::FieldMap& map = likelihood_->map();
  for (int tries = 0; tries < 10000; ++tries) {
    const double x = rng.uniform(-map.carpetHalfLength(), map.carpetHalfLength());
    const double y = rng.uniform(-map.carpetHalfWidth(), map.carpetHalfWidth());
    if (map.isFree(x, y, config_.free_space_margin_m))
      return math::SE2(x, y, rng.uniform(-math::kPi, math::kPi));
  }
  return math::SE2(0, 0, 0);
}

SampledImage PoseSearch::coarseImage(const cv::Mat& yuv, const Eigen::Isometry3d& base_to_optical,
                                     int pixel_stride) const {
  return likelihood_->sample(yuv, pixel_stride > 0 ? pixel_stride : config_.pixel_stride,
                             base_to_optical, background_.get());
}

void PoseSearch::fillUniform(std::vector<math::SE2>* pool, std::size_t n,
                             std::uint64_t seed) const {
  math::parallelFor(n, threads_, [&](std::size_t i) {
    math::Rng rng(math::mixSeeds(seed ^ 0x5bd1e995ull, i / 2));
    (*pool)[i] = uniformPose(rng);
    if (i % 2 == 1) (*pool)[i] = math::pointMirror((*pool)[i]);
  });
}

void PoseSearch::score(std::vector<math::SE2>* pool, std::vector<double>* ll, std::size_t first,
                       bool move, const math::SE2& odom_delta, const SampledImage& image,
                       const color::SwitchingColorFilter& lighting,
                       const Eigen::Isometry3d& base_to_optical) const {
  math::parallelFor(pool->size() - first, threads_, [&](std::size_t k) {
    const std::size_t i = first + k;
    if (move) (*pool)[i] = (*pool)[i] * odom_delta;
    (*ll)[i] +=
        likelihood_->logLikelihood(image, (*pool)[i], lighting, base_to_optical, nullptr, nullptr);
  });
}

void PoseSearch::pushWindow(const math::SE2& odom_delta, SampledImage image,
                            const color::SwitchingColorFilter& lighting,
                            const Eigen::Isometry3d& base_to_optical, bool reset) {
  if (reset) window_.clear();
  for (WindowFrame& f : window_) f.to_last = f.to_last * odom_delta;
  window_.push_back({std::move(image), math::SE2(), lighting, base_to_optical});
}

double PoseSearch::windowLogLikelihood(const math::SE2& pose_at_last) const {
  double sum = 0.0;
  for (const WindowFrame& f : window_)
    sum += likelihood_->logLikelihood(f.image, pose_at_last * f.to_last.inverse(), f.lighting,
                                      f.base_to_optical, nullptr, nullptr);
  return sum;
}

void PoseSearch::refine(std::vector<math::SE2>* pool, std::vector<double>* ll, std::size_t begin,
                        std::size_t end, int candidates, std::uint64_t seed) const {
  if (config_.refine_rounds <= 0 || end <= begin || window_.empty()) return;
  std::vector<std::size_t> top(end - begin);
  for (std::size_t i = 0; i < top.size(); ++i) top[i] = begin + i;
  const std::size_t k =
      std::min<std::size_t>(top.size(), static_cast<std::size_t>(std::max(candidates, 0)));
  std::partial_sort(top.begin(), top.begin() + static_cast<std::ptrdiff_t>(k), top.end(),
                    [&](std::size_t a, std::size_t b) { return (*ll)[a] > (*ll)[b]; });
  top.resize(k);
  for (int round = 0; round < config_.refine_rounds; ++round) {
    const double scale = std::ldexp(1.0, -round);
    math::parallelFor(k, threads_, [&](std::size_t c) {
      const std::size_t i = top[c];
      math::Rng rng(math::mixSeeds(math::mixSeeds(seed, static_cast<std::uint64_t>(round)), i));
      for (int t = 0; t < config_.refine_tries; ++t) {
        const math::SE2& p = (*pool)[i];
        const math::SE2 q(
            p.x_m + rng.gaussian(0.0, scale * config_.refine_sigma_m),
            p.y_m + rng.gaussian(0.0, scale * config_.refine_sigma_m),
            math::wrapAngle(p.yaw_rad + rng.gaussian(0.0, scale * config_.refine_sigma_rad)));
        const double l = windowLogLikelihood(q);
        if (l > (*ll)[i]) {
          (*pool)[i] = q;
          (*ll)[i] = l;
        }
      }
    });
  }
}

double PoseSearch::settle(PoseContest* contest, int candidates, std::uint64_t seed) const {
  std::vector<double>& ll = contest->log_likelihoods;
  const std::size_t split = contest->candidates;
  refine(&contest->poses, &ll, 0, split, candidates, seed);
  refine(&contest->poses, &ll, split, contest->poses.size(), candidates, seed ^ 0x9E37ull);
  const auto mid = ll.begin() + static_cast<std::ptrdiff_t>(split);
  const double best_candidate = split > 0 ? *std::max_element(ll.begin(), mid) : -1e300;
  const double best_particle = *std::max_element(mid, ll.end());
  return best_candidate - best_particle;
}

std::vector<std::size_t> PoseSearch::draw(const std::vector<double>& ll, std::size_t n, int count,
                                          math::Rng& rng) const {
  std::vector<double> w;
  const double target = 0.5 * count;
  auto weigh = [&](double lambda) {
    std::vector<double> logw(n);
    for (std::size_t i = 0; i < n; ++i) logw[i] = lambda * ll[i];
    math::normalizeLogWeights(logw, &w);
    return math::effectiveSampleSize(w);
  };
  double lo = 0.0, hi = 1.0;
  if (weigh(1.0) >= target) {
    lo = 1.0;
  } else {
    for (int it = 0; it < 30; ++it) {
      const double mid = 0.5 * (lo + hi);
      (weigh(mid) >= target ? lo : hi) = mid;
    }
  }
  weigh(lo);
  return math::resampleIndices(w, count, math::ResamplingScheme::kSystematic, rng);
}

}  // namespace adaptive_perception::localization
