#pragma once
// A search for the robot's pose over the whole field, the engine of the global localization and of
// the relocalization check: a pool of poses is scored on a coarse pixel grid image after image
// (each pose moved by the odometry, its log-likelihoods summed), the best poses are refined by
// hill-climbing over the search's images, and poses are drawn from the pool by their scores.
//
// Contract:
//  - Uniform poses lie where a robot can stand (free_space_margin_m from the field's walls and
//    goals); a pool is filled in point-mirrored pairs (entry 2k + 1 is the mirror of 2k), so both
//    halves of the point-symmetric field are searched alike.
//  - Every random draw but draw()'s comes from a stream seeded by (seed, index), so scores, pools
//    and refinements are the same for any thread count.
//  - The window holds the running search's images with the odometry from each to the last one; a
//    pose at the last image is scored over all of them (windowLogLikelihood).
#include <cstdint>
#include <memory>
#include <vector>

#include "adaptive_perception/localization/image_likelihood.h"
#include "adaptive_perception/math/rng.h"

namespace adaptive_perception::localization {

struct PoseSearchConfig {
  double free_space_margin_m = 0.15;  // uniform poses are drawn where a robot can stand
  // The coarse grid the searches score on: every pixel_stride-th pixel (of an image
  // ImageLikelihoodConfig::reference_width_px wide).
  int pixel_stride = 12;
  // Refinement on a search's last image: a pool of uniform poses lies some 0.14 m and 0.14 rad
  // apart, coarser than the likelihood's pose tolerance, so the pose nearest the truth can score
  // below a wrong one that happens to fit. A search's best poses are hill-climbed over all its
  // images: refine_rounds rounds of refine_tries perturbations each (Gaussian, refine_sigma_m /
  // refine_sigma_rad, halved every round), a perturbation replacing its pose when it scores
  // higher. 0 rounds turns it off.
  int refine_rounds = 3;
  int refine_tries = 6;
  double refine_sigma_m = 0.08;
  double refine_sigma_rad = 0.08;
  /// Its parameters' names, ranges and docs; defined in rbpf_configs.cpp.
  static const config::Fields<PoseSearchConfig>& fields();
  void validate() const { fields().validate(*this); }
};

/// Poses scored side by side over a search's window: a search's candidates [0, candidates) and the
/// particles' poses after them, with their summed log-likelihoods.
struct PoseContest {
  std::vector<math::SE2> poses;
  std::vector<double> log_likelihoods;
  std::size_t candidates = 0;
};

class PoseSearch {
 public:
  /// config is validated (std::invalid_argument naming the field).
  PoseSearch(std::shared_ptr<const ImageLikelihood> likelihood, const PoseSearchConfig& config,
             int threads);

  /// A pose uniform over where a robot can stand (the field's centre after 10000 misses).
  math::SE2 uniformPose(math::Rng& rng) const;
  /// The image on the search's coarse grid (or every pixel_stride-th pixel, when > 0), with
  /// offsets for the camera at base_to_optical (and the background density of setBackground()).
  SampledImage coarseImage(const cv::Mat& yuv, const Eigen::Isometry3d& base_to_optical,
                           int pixel_stride = 0) const;
  /// The current image's background density (null: the uniform density), for coarseImage().
  void setBackground(std::shared_ptr<const BackgroundDensity> background) {
    background_ = std::move(background);
  }
  /// pool[i] for i < n: uniform poses in point-mirrored pairs.
  void fillUniform(std::vector<math::SE2>* pool, std::size_t n, std::uint64_t seed) const;
  /// Moves pool[first..] by odom_delta (when `move`) and adds each pose's log-likelihood of `image`
  /// to ll.
  void score(std::vector<math::SE2>* pool, std::vector<double>* ll, std::size_t first, bool move,
             const math::SE2& odom_delta, const SampledImage& image,
             const color::SwitchingColorFilter& lighting,
             const Eigen::Isometry3d& base_to_optical) const;

  /// Adds an image to the window (after the earlier ones are moved on by odom_delta); `reset`
  /// empties it first.
  void pushWindow(const math::SE2& odom_delta, SampledImage image,
                  const color::SwitchingColorFilter& lighting,
                  const Eigen::Isometry3d& base_to_optical, bool reset);
  void clearWindow() { window_.clear(); }
  /// The summed log-likelihood over the window's images of a pose at the last image.
  double windowLogLikelihood(const math::SE2& pose_at_last) const;
  /// Hill-climbs the `candidates` best poses of pool[begin..end) over the window (see
  /// PoseSearchConfig::refine_rounds); ll holds their window log-likelihoods and is updated.
  void refine(std::vector<math::SE2>* pool, std::vector<double>* ll, std::size_t begin,
              std::size_t end, int candidates, std::uint64_t seed) const;
  /// Both sides of a contest refined alike (`candidates` best poses of each), so neither wins by
  /// having been optimised on these images; returns the best candidate's log-likelihood minus the
  /// best particle pose's.
  double settle(PoseContest* contest, int candidates, std::uint64_t seed) const;
  /// `count` indices into pool[0..n) drawn (systematic resampling) by the summed log-likelihoods,
  /// flattened by the largest factor <= 1 that leaves an effective sample size of count / 2.
  std::vector<std::size_t> draw(const std::vector<double>& ll, std::size_t n, int count,
                                math::Rng& rng) const;

  const ImageLikelihood& likelihood() const { return *likelihood_; }
  int threads() const { return threads_; }

 private:
  struct WindowFrame {
    SampledImage image;
    math::SE2 to_last;  // the odometry from this image to the last one
    color::SwitchingColorFilter lighting;
    Eigen::Isometry3d base_to_optical;
  };
  std::shared_ptr<const ImageLikelihood> likelihood_;
  PoseSearchConfig config_;
  int threads_;
  std::vector<WindowFrame> window_;
  std::shared_ptr<const BackgroundDensity> background_;
};

}  // namespace adaptive_perception::localization
