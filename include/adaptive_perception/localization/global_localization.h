#pragma once
// Global localization of the RBPF: where on the field is the robot, from images alone.
//
// After start(), the next search_frames images score pool_size uniform poses on the search's
// coarse grid (each pose moved by the odometry between images, its log-likelihoods summed, under
// the priors' lighting), and the particles are drawn from the pool at every image; so every part of
// the field is searched, not just where N random particles happened to land, and the particles
// commit only once several views agree (one view of lines rarely tells where on the field the
// robot is). On the last of those images the refine_candidates best poses are refined first.
//
// Second draw: the pool goes on being scored until confirm_frames images; then confirm_fraction of
// the particles are drawn from the pool again (with the best particle's lighting) and the rest are
// kept, so the next images choose between the particles' hypotheses and the pool's. A start that
// sees only a wall and a line for its first images commits to any place that looks like that; the
// view that tells them apart comes a second later, when no particle is left near the truth (the
// dark bag's global starts: docs/nodes/rbpf_localizer.md). A pool drawn from a goal's proposals has
// no second draw: its poses all see the goal where it is seen, and its contest with the particles
// would be one between poses and their point mirrors, which the likelihood cannot decide and the
// mirror test does (on the NAO development images it handed a point that had committed right to
// its mirror).
//
// Contract: the class holds the pool and says what it decided; the caller (RbpfLocalizer) owns the
// particles and applies the decision.
#include <cstdint>
#include <optional>
#include <vector>

#include "adaptive_perception/localization/pose_search.h"

namespace adaptive_perception::localization {

struct GlobalLocalizationConfig {
  int pool_size = 60000;  // 0 turns the search off (the N uniform particles are used as they are)
  int search_frames = 4;  // images scored before the particles commit
  // The second draw (see above): at most search_frames, or a fraction of 0, turns it off.
  int confirm_frames = 8;
  double confirm_fraction = 0.5;
  int refine_candidates = 100;  // poses refined at the commit and at the second draw (a side)
  // Share of the pool drawn from the goals the first search image shows (goal_detection.h: the
  // poses that see the goal where it is seen, with the sighting's uncertainty), the rest uniform;
  // none seen, all uniform. A uniform pool puts a pose within 0.07 m and 0.07 rad of the truth
  // only by chance, and on a real camera a wrong pose seen on the coarse grid can win (docs/
  // field_localization.md); a goal's posts narrow the field to a few arcs. All of the pool: with
  // half of it uniform, as a guard against a false goal, a uniform pose elsewhere won again on a
  // development point (punt5, 6.25 m off).
  double goal_pool_share = 1.0;
  // A pool from a goal lies on a few arcs, not over the whole field: fewer poses cover it, and a
  // finer grid sees the lines that choose where along the arc the robot stands (at the uniform
  // search's stride, 37 px of a 640-wide image, a development point facing the goal head-on ended
  // on its mirror or along the arc for 2 of 8 seeds; with these, 8 of 8 within 0.3 m, and each
  // image costs about what the uniform pool's does: docs/field_localization.md).
  int goal_pool_size = 15000;
  int goal_pixel_stride = 6;  // px of an ImageLikelihoodConfig::reference_width_px-wide image
  /// Its parameters' names, ranges and docs; defined in rbpf_configs.cpp.
  static const config::Fields<GlobalLocalizationConfig>& fields();
  void validate() const { fields().validate(*this); }
};

class GlobalLocalization {
 public:
  explicit GlobalLocalization(const GlobalLocalizationConfig& config);

  /// Starts a search (a no-op with pool_size 0): the next images go to searchImage().
  void start();
  /// Ends any search and second draw (the particles were placed otherwise).
  void stop();
  /// From start() until the particles commit.
  bool searching() const { return searching_; }
  /// After the commit, until the second draw.
  bool confirming() const { return confirming_; }

  struct SearchStep {
    std::vector<math::SE2> poses;  // the particles' poses, drawn from the pool
    bool committed = false;        // the last image of the search: the particles commit
  };
  /// True before the search's first image: the pool is filled at the next searchImage().
  bool poolPending() const { return searching_ && pool_.empty(); }
  /// One image while searching(): the pool's poses move by odom_delta (from the second image on)
  /// and take this image's score; `count` poses are drawn from it with `rng`. On the first image
  /// the pool is filled: with `proposals`, goal_pool_size poses on the goal_pixel_stride grid (at
  /// most goal_pool_share of them the proposals, in mirrored pairs, the rest uniform); without,
  /// pool_size uniform poses on the search's grid.
  SearchStep searchImage(PoseSearch* search, const math::SE2& odom_delta, const cv::Mat& yuv,
                         const color::SwitchingColorFilter& lighting,
                         const Eigen::Isometry3d& base_to_optical, std::uint64_t seed, int count,
                         math::Rng& rng, const std::vector<math::SE2>& proposals = {});
  /// One image while confirming() (after the particles took this image's motion): on the last one,
  /// the contest of the pool against `particle_poses` over the search's images (before refinement).
  std::optional<PoseContest> confirmImage(PoseSearch* search, const math::SE2& odom_delta,
                                          const cv::Mat& yuv,
                                          const color::SwitchingColorFilter& lighting,
                                          const Eigen::Isometry3d& base_to_optical,
                                          const std::vector<math::SE2>& particle_poses);

  const GlobalLocalizationConfig& config() const { return config_; }

 private:
  void clearPool();

  GlobalLocalizationConfig config_;
  bool searching_ = false;
  bool confirming_ = false;
  std::vector<math::SE2> pool_;  // moved by the odometry
  std::vector<double> pool_ll_;  // their summed log-likelihoods
  int frames_ = 0;               // images scored on the pool so far
  bool from_proposals_ = false;  // the pool holds proposals: no second draw
  int pixel_stride_ = 0;         // the running search's grid (0: the PoseSearch's)
};

}  // namespace adaptive_perception::localization
