#pragma once
// Rao-Blackwellised particle filter over camera pose and lighting (Schulz & Fox 2004, section IV).
//
// Each particle holds a robot pose (x, y, yaw in map) and its own switching Kalman filter over the
// lighting (color::SwitchingColorFilter). Per image:
//   1. predict the pose from the odometry delta (MotionModel) and the lighting by its drift (eq.
//   6);
//   2. weight by the image likelihood of eq. (16): the product over a pixel subsample of eq. (9),
//   with the
//      map colour each pixel should show from the particle's camera pose (label renderer) and the
//      particle's predicted lighting. The paper skips background pixels; here a pixel that is
//      background under a pose gets the uniform density over the YUV cube instead, because skipping
//      makes poses that see more background win for having fewer (negative) terms. For real data
//      the pixel likelihood is a mixture with a uniform density over the YUV cube (outliers:
//      robots, people, mislabelled edges) and the product is tempered by an exponent (neighbouring
//      pixels are not independent);
//   3. update the particle's lighting with the colour means of its own pixel labels (section IV-B);
//   4. resample (low variance) when the effective sample size falls below a fraction of N; inject
//   uniform
//      particles when the short-term average likelihood drops below the long-term one (augmented
//      MCL: recovery from kidnapping).
// Per-particle work runs on `threads` threads; every particle draws from its own random stream
// seeded by (seed, frame, particle), so the result is the same for any thread count.
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/color/switching_color_filter.h"
#include "adaptive_perception/localization/motion_model.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/world/label_renderer.h"

namespace adaptive_perception::localization {

struct ImageLikelihoodConfig {
  int pixel_stride = 4;  // use every stride-th pixel in x and y (a regular grid)
  double outlier_probability =
      0.1;                 // weight of the uniform density in the pixel likelihood mixture
  double exponent = 0.02;  // the image log-likelihood is multiplied by this
  // Each grid pixel is scored under a mixture of the colours the pose predicts: half the colour at
  // the pixel, an eighth each the colours at the grid pixels a pose error of position_tolerance_m
  // and heading_tolerance_rad would move it to (left/right and up/down, in whole grid steps, at
  // most max_neighbourhood_cells). A pixel-exact
  // comparison punishes a pose a few centimetres off twice, where a line is predicted and where it
  // is seen, so near the robot (a low camera, lines a few decimetres away) it scores below poses
  // that see no line at all, and the particles drift off a true peak only 1-2 cm wide. The
  // offsets follow the ground distance each pixel looks at (the camera's height and tilt are the
  // same for every particle, so they are computed once per image): a near pixel moves far in the
  // image for a small pose error, a far one hardly at all, and a fixed image-space neighbourhood
  // would either not help near or blur the range of far lines. The neighbours are grid pixels, so
  // it costs no extra rays. Tolerance 0: the pixel alone (the paper).
  double position_tolerance_m = 0.05;
  double heading_tolerance_rad = 0.02;
  int max_neighbourhood_cells = 4;
  // The strides (pixel_stride, RbpfConfig::global_pixel_stride) are in pixels of an image this
  // wide (the ERS-7's). A camera of another width samples the same directions: its strides are
  // scaled with its width, and the exponent by the reference grid's pixel count over its own, so
  // that an image weighs the same at any resolution (RbpfConfig::forCamera).
  int reference_width_px = 208;
  void validate() const;
};

struct RbpfConfig {
  int particles = 500;
  MotionModelConfig motion;
  ImageLikelihoodConfig likelihood;
  color::ColorModelConfig model = rbpfModelConfig();
  color::SwitchingFilterConfig switching;
  double resample_ess_fraction = 0.5;  // resample when ESS < this * N
  // Adaptive tempering: an image whose likelihood would leave fewer than this fraction of the
  // particles effective is flattened until it leaves that many (0 turns it off).
  double min_ess_fraction = 0.0;
  // Augmented MCL on the per-pixel average log-likelihood: EMA rates, and the fraction of particles
  // re-drawn uniformly per nat the fast average lies below the slow one (capped).
  double recovery_alpha_slow = 0.05;
  double recovery_alpha_fast = 0.5;
  double recovery_gain_per_nat = 0.5;
  double recovery_max_fraction =
      0.0;  // off by default: as tuned so far it also fires at light switches
  double free_space_margin_m = 0.15;  // uniform particles are drawn where a robot can stand
  // Global localization: after initUniform(), the next global_search_frames images score this many
  // uniform poses on a coarse pixel grid (every global_pixel_stride-th pixel), each pose moved by
  // the odometry between images and its log-likelihoods summed, and the particles are drawn from
  // them; so every part of the field is searched, not just where N random particles happened to
  // land, and the particles commit only once several views agree (one view of lines rarely tells
  // where on the field the robot is). Until then the particles are redrawn from the pool at every
  // image. 0 turns the pool off (the N uniform particles are used as they are).
  int global_pool_size = 60000;
  int global_search_frames = 4;
  // Second draw of a global search: the particles commit after global_search_frames images, but
  // the pool goes on being scored until global_confirm_frames images; then
  // global_confirm_fraction of the particles are drawn from the pool again (as at the commit,
  // with the best particle's lighting) and the rest are kept (drawn by weight), so the next
  // images choose between the particles' hypotheses and the pool's. A start that sees only a
  // wall and a line for its first images commits to any of the places that look like that, and
  // the view that tells them apart comes a second later, when no particle is left near the truth
  // (the dark bag: 2 of 5 seeds converged with one draw, 5 of 5 with the second). Scoring the
  // pool longer before committing does not serve instead: the pool's poses follow the odometry
  // without noise, and over 8 images of turning on the spot they fall out of line with the images
  // (the bright bag: 1 of 5 seeds converged when committing after 8). Nor does comparing the
  // pool's best pose with the particles' (as the relocalization check does): on the dark bag
  // the particles' best wrong pose scored within 1 nat of the pool's best over the 8 images; it
  // is the pool's spread of hypotheses that holds the truth. The score of that comparison is
  // still reported (StepResult::relocalization_score). At most global_search_frames, or a
  // fraction of 0, turns it off.
  int global_confirm_frames = 8;
  double global_confirm_fraction = 0.5;
  // The field's lines are point-symmetric about the centre spot; only the goal and beacon colours
  // tell the halves apart, and they are in view for a few frames only. At each resampling this
  // fraction of the particles is replaced by the point mirror (-x, -y, yaw + pi) of other
  // particles, so the other half's hypothesis stays alive until colours decide between them.
  // The copies take mirror_relative_weight (below).
  double mirror_fraction = 0.05;
  // The weight of a mirrored particle relative to the others (0 < w <= 1). Below 1 the mirrors keep
  // the other half's hypothesis alive without moving weight to it: with weight 1, every resampling
  // while the view is symmetric moved mirror_fraction of the weight across, and after a few
  // seconds of lines only the mirror held half the weight and the estimate could flip to it.
  double mirror_relative_weight = 0.05;
  // Mirror test: after the particles have committed, every image scores the pose estimate and its
  // point mirror side by side under one reference lighting, and sums the log-likelihood ratio
  // (mirror minus estimate, tempered nats) over the images, older images fading with time
  // constant mirror_test_memory_s. The lines score alike for both, so the sum is the evidence of
  // the goals and beacons alone. When it exceeds mirror_test_margin_nats, the particles of the
  // estimate's cluster move to their mirrors (and take the reference lighting) and the sum changes
  // sign, as it does when the estimate moves to the mirror cluster on its own; a relocalization
  // or another jump of the estimate by more than 0.5 m starts it again. The
  // reference lighting is a switching filter from the priors updated with the green and white means
  // only, the colours that look alike from both poses: a particle's own lighting learns the colours
  // under its own labels, so a particle on the mirror learns that its "cyan" beacon band is yellow,
  // and then it explains the very pixels that should have told it apart (on the bright bag the true
  // pose led its mirror by some 30 nats over the run and still lost the weight to it). The memory
  // lets new evidence overturn old within seconds: a kidnap that puts the robot near the mirror of
  // where it was goes on fitting the lines, and with a sum clipped at 20 nats instead, the evidence
  // from before the kidnap held the particles on the wrong half. 0 turns the test off.
  double mirror_test_margin_nats = 3.0;
  double mirror_test_memory_s = 4.0;
  int global_pixel_stride = 12;
  // Refinement of a search (the global search and the relocalization check) on its last image: a
  // pool of uniform poses lies some 0.14 m and 0.14 rad apart, coarser than the likelihood's pose
  // tolerance, so the pose nearest the truth can score below a wrong one that happens to fit. The
  // refine_candidates best poses are hill-climbed over all the search's images (each image kept
  // on the coarse grid with its odometry to the last one): refine_rounds rounds of refine_tries
  // perturbations each (Gaussian, refine_sigma_m / refine_sigma_rad, halved every round), a
  // perturbation replacing its pose when it scores higher. 0 rounds turns it off.
  int refine_candidates = 100;
  int refine_rounds = 3;
  int refine_tries = 6;
  double refine_sigma_m = 0.08;
  double refine_sigma_rad = 0.08;
  // Relocalization check (recovers from a kidnap, and from a global search that committed to the
  // wrong place): every relocalization_interval_s seconds after the particles have committed,
  // relocalization_pool_size uniform poses (in point-mirrored pairs) and the particles' own poses
  // are scored side by side over the next global_search_frames images as the global search scores
  // its pool (every global_pixel_stride-th pixel, each pose moved by the odometry, log-likelihoods
  // summed), all under the priors' lighting, as in the global search; the
  // relocalization_refine_candidates best poses of both sides are refined alike (refine_rounds,
  // refine_tries, refine_sigma_*). If the best uniform pose beats the best particle pose by more
  // than relocalization_margin (tempered log-likelihood summed over those images), the check has
  // found that the particles are lost, and by default (relocalization_restart) the global search
  // starts again on the next image, with its full pool and its second draw. With
  // relocalization_restart false, relocalization_fraction of the particles are drawn from the
  // check's own poses instead (with the priors' lighting) and the rest are kept (drawn by weight).
  // The check then only has to tell that something beats the particles, not where the robot is,
  // so it is small: on 4 simulated kidnaps x 5 seeds (scripts/evaluate_localization.sh), a check
  // every 1 s of 2000 poses and 20 refined candidates with the restart re-converged 18 of 20
  // within 5 s; the draw from 5000 poses and 100 candidates 15 of 20, at twice the cost. A
  // restart check of 5000 poses every 2 s instead of 1 s, 2 of 20: a check whose 4 images fit
  // several places misses, so it has to come often (every 0.5 s gained nothing: 17 of 20). A
  // likelihood ratio against the rest of the field, not the likelihood's level: the level
  // swings with what the camera sees and with the light, and falls as far when the head turns to a
  // bare stretch of carpet as after a kidnap. Not the particles' own lighting: it has learnt the
  // colours under the particles' labels, after a kidnap those of the wrong place, and it favours
  // their hypothesis (with the draw, 12 of 20 kidnaps instead of 15, and correct tracks moved away
  // on 2 of 5 global starts of one bag). Cost: bench_rbpf --particles 100 --threads 1 gives about
  // half the frame rate without the check (see docs/nodes/rbpf_localizer.md). 0 turns it off.
  double relocalization_interval_s = 1.0;
  int relocalization_pool_size = 2000;
  double relocalization_margin = 2.0;
  double relocalization_fraction = 0.5;
  bool relocalization_restart = true;
  int relocalization_refine_candidates = 20;
  int threads = 1;
  std::uint64_t seed = 1;

  /// The colour model for the particles: the default colours with a lower pixel minimum, as each
  /// particle sees only the subsample, and an observation noise floor of 25 levels^2 (5 levels sd,
  /// not 2): a particle's labels come from a pose that is a few centimetres off, so its colour
  /// means mix in the neighbouring colour, and trusted at 2 levels they made the particles'
  /// lighting jitter apart by several tempered nats per image, enough to hand the weight to a
  /// wrong hypothesis (on the bright bag a global start converged for 1 seed in 5 with 4, 3 in 5
  /// with 25, 1 in 5 with 100).
  static color::ColorModelConfig rbpfModelConfig();
  void validate() const;
  /// This configuration as a camera of that size runs it: strides scaled with the width over
  /// likelihood.reference_width_px, the exponent with the pixel count (the same configuration for a
  /// camera of the reference width). RbpfLocalizer applies it; config() returns the result.
  RbpfConfig forCamera(const world::PinholeCamera& camera) const;
};

/// How many grid steps a pixel's neighbours lie left/right (du) and up/down (dv).
struct NeighbourOffset {
  std::uint8_t du = 0, dv = 0;
};

/// Per pixel of a `stride`-spaced grid, the grid steps that a pose error of
/// config.position_tolerance_m / heading_tolerance_rad moves it by, for a camera at
/// base_to_optical above the ground plane z = 0 of base_link.
std::vector<NeighbourOffset> neighbourOffsets(const world::PinholeCamera& camera,
                                              const std::vector<world::PixelCoord>& pixels,
                                              int stride, const Eigen::Isometry3d& base_to_optical,
                                              const ImageLikelihoodConfig& config);

struct Particle {
  math::SE2 pose;
  color::SwitchingColorFilter lighting;
  double log_likelihood = 0.0;  // of the last image
};

class RbpfLocalizer {
 public:
  RbpfLocalizer(const world::FieldMap& map, const world::PinholeCamera& camera,
                const std::vector<color::LightingPrior>& priors, const RbpfConfig& config);

  /// Global localization: poses uniform over the free field, lighting filters at their priors.
  void initUniform();
  /// Poses from N(mean, cov) (x, y, yaw).
  void initGaussian(const math::SE2& mean, const Eigen::Matrix3d& cov);

  struct StepResult {
    double effective_sample_size = 0.0;
    bool resampled = false;
    int injected = 0;
    int mirrored = 0;
    double tempering = 1.0;  // the factor applied to this image's log-likelihood (1: none)
    double mean_pixel_log_likelihood = 0.0;  // per used pixel, of the average particle likelihood
    int pixels_used = 0;                     // by the best particle
    // A relocalization check (or the second draw of a global search) that ended with this
    // image: the best uniform pose's summed
    // log-likelihood minus the best particle pose's (NaN: no check ended), and whether the
    // particles were redrawn.
    double relocalization_score = std::numeric_limits<double>::quiet_NaN();
    bool relocalized = false;
    // The mirror test's evidence for the mirror of the estimate after this image (0: not run) and
    // whether the particles were moved to their mirrors.
    double mirror_evidence = 0.0;
    bool mirror_flipped = false;
  };
  /// One image: odometry delta since the previous image (in the previous base frame), elapsed time,
  /// the YUV image (CV_8UC3) and the camera pose on the robot (base_link -> camera_optical_frame).
  StepResult step(const math::SE2& odom_delta, double dt_s, const cv::Mat& yuv,
                  const Eigen::Isometry3d& base_to_optical);

  /// Takes the image's pixel subsample (called by step(); public for tests and tools).
  void setImage(const cv::Mat& yuv);
  /// The tempered eq. (16) log-likelihood of the current image for a robot pose and lighting
  /// estimate; fills `obs` (may be null) with the colour means under that pose's labels and `used`
  /// with the number of pixels showing a map colour.
  double imageLogLikelihood(const math::SE2& pose, const color::SwitchingColorFilter& lighting,
                            const Eigen::Isometry3d& base_to_optical, color::ColorObservation* obs,
                            int* used) const;
  /// True from initUniform() until step() has scored global_search_frames images on the pool.
  bool globalSearchPending() const { return global_pending_; }

  const std::vector<Particle>& particles() const { return particles_; }
  const std::vector<double>& weights() const { return weights_; }
  struct PoseEstimate {
    math::SE2 pose;               // weighted mean (circular in yaw) of the main cluster
    Eigen::Matrix3d covariance;   // of the main cluster (x, y, yaw)
    double cluster_weight = 0.0;  // share of the weight in the main cluster
    double spread_m = 0.0;        // sqrt(trace of the x-y covariance) of ALL particles
  };
  /// The pose estimate: the weighted mean of the main cluster (the heaviest 3x3x3 block of a
  /// 0.25 m x 45 degree grid, and the particles within 0.5 m and 0.6 rad of its mean), not of all
  /// particles, whose mean may lie between two hypotheses.
  PoseEstimate estimate() const;
  /// The particle with the highest weight.
  const Particle& best() const;
  const RbpfConfig& config() const { return config_; }
  const std::vector<world::PixelCoord>& pixels() const { return pixels_; }

 private:
  void weighParticle(size_t i, const math::SE2& odom_delta, double dt_s,
                     const Eigen::Isometry3d& base_to_optical, std::uint64_t frame_seed);
  math::SE2 uniformPose(math::Rng& rng) const;
  std::vector<size_t> mainCluster() const;
  math::SE2 weightedMean(const std::vector<size_t>& idx) const;
  Eigen::Matrix3d covarianceAbout(const std::vector<size_t>& idx, const math::SE2& mean) const;
  double logLikelihoodAt(const std::vector<world::PixelCoord>& pixels, int grid_cols,
                         const std::vector<NeighbourOffset>& offsets,
                         const std::vector<Eigen::Vector3d>& yuv, const math::SE2& pose,
                         const color::SwitchingColorFilter& lighting,
                         const Eigen::Isometry3d& base_to_optical, color::ColorObservation* obs,
                         int* used) const;
  /// The image on the coarse grid of the global search and the relocalization check.
  struct CoarseImage {
    std::vector<world::PixelCoord> pixels;
    int cols = 0;
    std::vector<Eigen::Vector3d> values;
    std::vector<NeighbourOffset> offsets;
  };
  CoarseImage coarseImage(const cv::Mat& yuv, const Eigen::Isometry3d& base_to_optical) const;
  /// Moves pool[first..] by odom_delta (when `move`) and adds each pose's coarse log-likelihood.
  void scorePool(std::vector<math::SE2>* pool, std::vector<double>* ll, size_t first, bool move,
                 const math::SE2& odom_delta, const CoarseImage& image,
                 const color::SwitchingColorFilter& lighting,
                 const Eigen::Isometry3d& base_to_optical) const;
  /// pool[i] for i < n: a uniform pose, odd entries the point mirror of the even one before.
  void fillUniformPool(std::vector<math::SE2>* pool, size_t n, std::uint64_t seed) const;
  /// The summed coarse log-likelihood over the search's images of a pose at the last image.
  double windowLogLikelihood(const math::SE2& pose_at_last) const;
  /// Adds an image to the search window (the earlier ones move on by odom_delta).
  void pushWindow(const math::SE2& odom_delta, CoarseImage image,
                  const color::SwitchingColorFilter& lighting,
                  const Eigen::Isometry3d& base_to_optical, bool reset);
  /// Hill-climbs the `candidates` best poses of pool[begin..end) over the window (see
  /// refine_rounds); ll holds their window log-likelihoods and is updated with them.
  void refinePool(std::vector<math::SE2>* pool, std::vector<double>* ll, size_t begin, size_t end,
                  int candidates, std::uint64_t seed) const;
  /// `count` particles drawn from pool[0..n) weighted by the summed log-likelihoods, flattened
  /// as far as needed to leave half of them distinct.
  std::vector<Particle> drawFromPool(const std::vector<math::SE2>& pool,
                                     const std::vector<double>& ll, size_t n, int count,
                                     const color::SwitchingColorFilter& lighting);
  /// One image of the global search; returns true once the pool has seen global_search_frames.
  bool globalSearch(const math::SE2& odom_delta, const cv::Mat& yuv,
                    const Eigen::Isometry3d& base_to_optical, std::uint64_t frame_seed);
  /// One image of the relocalization check (after the particles were weighed and resampled).
  void relocalizationCheck(const math::SE2& odom_delta, double dt_s, const cv::Mat& yuv,
                           const Eigen::Isometry3d& base_to_optical, std::uint64_t frame_seed,
                           StepResult* result);
  /// One image of the second draw of a global search (see global_confirm_frames).
  void confirmSearch(const math::SE2& odom_delta, const cv::Mat& yuv,
                     const Eigen::Isometry3d& base_to_optical, std::uint64_t frame_seed,
                     StepResult* result);
  /// What the end of a search does: redraw when the search's best pose beats the particles' by
  /// `margin`; then either restart the global search (`restart`) or draw `fraction` of the
  /// particles from the search's poses. Both sides' refine_candidates best poses are refined.
  struct CheckPolicy {
    double margin;
    double fraction;
    bool restart;
    int refine_candidates;
  };
  /// The end of a relocalization check or a second draw: check_pool_ holds the search's poses
  /// [0, check_uniform_) and the particles' poses after them, check_ll_ their window
  /// log-likelihoods; both sides are refined and compared, and the particles redrawn (with
  /// `lighting`) as `policy` says when the search wins.
  void finishCheck(const color::SwitchingColorFilter& lighting, std::uint64_t frame_seed,
                   const CheckPolicy& policy, StepResult* result);
  /// The mirror test on the current image (see RbpfConfig::mirror_test_margin_nats).
  void mirrorTest(const math::SE2& odom_delta, double dt_s,
                  const Eigen::Isometry3d& base_to_optical, StepResult* result);
  /// Forgets the mirror test's evidence and reference lighting.
  void resetMirrorTest();
  template <typename F>
  void parallelFor(size_t n, F&& f) const;

  world::FieldMap map_;
  world::LabelRenderer renderer_;
  std::vector<color::LightingPrior> priors_;
  RbpfConfig config_;
  math::Rng rng_;
  std::vector<Particle> particles_;
  std::vector<double> weights_;
  std::vector<world::PixelCoord> pixels_;
  int grid_cols_ = 0;                     // pixels_ is a grid_cols_-wide row-major grid
  std::vector<NeighbourOffset> offsets_;  // for the camera at offsets_camera_ (step())
  Eigen::Isometry3d offsets_camera_ = Eigen::Isometry3d(Eigen::Matrix4d::Zero());
  std::vector<Eigen::Vector3d> pixel_yuv_;  // the current image at pixels_
  std::vector<int> pixels_used_;
  std::uint64_t frame_ = 0;
  double w_slow_ = 0.0, w_fast_ = 0.0;
  bool have_average_ = false;
  bool global_pending_ = false;
  std::vector<math::SE2> pool_;   // the global search's poses, moved by odometry
  std::vector<double> pool_ll_;   // and their summed log-likelihoods
  int pool_frames_ = 0;           // images scored on the pool so far
  bool confirm_pending_ = false;  // the particles committed; the pool goes on to confirm them
  // The images of the running search, on the coarse grid, with the odometry to the last one.
  struct WindowFrame {
    CoarseImage image;
    math::SE2 to_last;
    color::SwitchingColorFilter lighting;
    Eigen::Isometry3d base_to_optical;
  };
  std::vector<WindowFrame> window_;
  // The relocalization check: uniform poses [0, check_uniform_) then the particles' poses.
  std::vector<math::SE2> check_pool_;
  std::vector<double> check_ll_;
  size_t check_uniform_ = 0;
  int check_frames_ = 0;              // images scored in the running check (0: none running)
  double seconds_since_check_ = 0.0;  // since the particles committed or the last check ended
  // The mirror test: the estimate it last scored, its evidence and its reference lighting.
  bool mirror_have_pose_ = false;
  math::SE2 mirror_pose_;
  double mirror_evidence_ = 0.0;
  color::SwitchingColorFilter mirror_lighting_;
};

}  // namespace adaptive_perception::localization
