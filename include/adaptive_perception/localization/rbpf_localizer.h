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
//   4. resample (low variance) when the effective sample size falls below a fraction of N, some
//      particles replaced by point mirrors of others (the field is point-symmetric);
//   5. the searches over the whole field that the particle filter alone cannot do, each in its own
//      part: the global search after initUniform() (global_localization.h), the check that the
//      particles are not lost (relocalization_monitor.h) and the test of which half of the field
//      the robot is on (mirror_test.h), on a common search engine (pose_search.h).
// Per-particle work runs on `threads` threads; every particle draws from its own random stream
// seeded by (seed, frame, particle), so the result is the same for any thread count.
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/color/switching_color_filter.h"
#include "adaptive_perception/color/white_balance.h"
#include "adaptive_perception/localization/centre_circle.h"
#include "adaptive_perception/localization/global_localization.h"
#include "adaptive_perception/localization/goal_detection.h"
#include "adaptive_perception/localization/image_likelihood.h"
#include "adaptive_perception/localization/mirror_test.h"
#include "adaptive_perception/localization/motion_model.h"
#include "adaptive_perception/localization/pose_cluster.h"
#include "adaptive_perception/localization/pose_search.h"
#include "adaptive_perception/localization/relocalization_monitor.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::localization {

struct RbpfConfig {
  int particles = 500;
  MotionModelConfig motion;
  ImageLikelihoodConfig likelihood;
  color::ColorModelConfig model = rbpfModelConfig();
  color::SwitchingFilterConfig switching;
  double resample_ess_fraction = 0.5;  // resample when ESS < this * N
  // At each resampling this fraction of the particles is replaced by the point mirror (-x, -y,
  // yaw + pi) of other particles, so the other half's hypothesis stays alive until the goal and
  // beacon colours decide between them (the field's lines are point-symmetric about the centre).
  double mirror_fraction = 0.05;
  // The weight of a mirrored particle relative to the others (0 < w <= 1). Below 1 the mirrors keep
  // the other half's hypothesis alive without moving weight to it: with weight 1, every resampling
  // while the view is symmetric moved mirror_fraction of the weight across, and after a few
  // seconds of lines only the mirror held half the weight and the estimate could flip to it.
  double mirror_relative_weight = 0.05;
  PoseSearchConfig search;              // the coarse grid and refinement of the searches
  GlobalLocalizationConfig global;      // the global search after initUniform()
  RelocalizationConfig relocalization;  // the check that the particles are not lost
  MirrorTestConfig mirror_test;         // which half of the field
  GoalDetectionConfig goals;            // goals seen, for the global search's pool
  CentreCircleConfig circle;            // the centre circle seen, for the same pool
  // The body's lean beyond the head chain's camera pose, as the goal seen at a global start
  // measures it (GoalSighting::pitch_offset_rad, applied by leanCamera()), is added to every
  // camera pose until the particles are placed anew (initUniform(), initGaussian(): a pose given
  // by hand comes without a goal to measure it). A legged robot's stance tilts its camera by more
  // than its head joints say (0.09 rad on one development point of docs/field_localization.md),
  // and the likelihood needs the pitch to a few thousandths of a radian.
  bool goal_pitch_correction = true;
  // At the first image after initUniform() / initGaussian() that shows carpet (the pose-free
  // segmentation's, at least the model's min_pixels_per_color), the priors (of the particles, the
  // searches and the mirror test) are adapted to that image without a pose
  // (color/image_adapted_prior.h): for a camera at a venue the priors were not learnt from, such
  // as a real robot's with the simulated venues' priors. Off for a venue of the priors: the
  // adaptation pulls every mode to the first image's lighting, and a switching filter's other mode
  // would then no longer be the other lighting.
  bool adapt_priors_to_image = false;
  // With adapt_priors_to_image, that image first gives the light's colour and brightness: the
  // line paint the pose-free segmentation finds in it is white by the rules, and every image until
  // the particles are placed anew is balanced so that this paint is grey at white_balance's
  // paint_luma (color/white_balance.h), before the priors are adapted, the goals and the centre
  // circle are looked for, and the particles and the mirror test read it. A tint of a tenth of a
  // channel's level (a warm evening light, a camera balanced for daylight) or a light 0.7 times as
  // bright otherwise moved the landmarks' hues and the goals' whiteness off what the thresholds
  // and priors expect, and sent points of the NAO development session to the field's mirror
  // (docs/field_localization.md). Off, or with adapt_priors_to_image off, images are used as they
  // come.
  bool balance_to_paint = true;
  color::WhiteBalanceConfig white_balance;
  // When the image the priors were adapted to gave no balance (no line paint in view, or none
  // white enough), every this many images another is tried (36 ms at 640 x 480), and the first
  // that gives one is adapted to again. 30: once a second of a NAO's camera. 0: never.
  int balance_retry_images = 30;
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
  /// Every field above but threads and seed (which tools and nodes read in their own ways), the
  /// nested configs' included; defined in rbpf_configs.cpp.
  static const config::Fields<RbpfConfig>& fields();
  void validate() const;
  /// This configuration as a camera of that size runs it: strides scaled with the width over
  /// likelihood.reference_width_px, the exponent with the pixel count (the same configuration for a
  /// camera of the reference width). RbpfLocalizer applies it; config() returns the result.
  RbpfConfig forCamera(const world::PinholeCamera& camera) const;
};

struct Particle {
  math::SE2 pose;
  color::SwitchingColorFilter lighting;
  double log_likelihood = 0.0;  // of the last image
};

class RbpfLocalizer {
 public:
  RbpfLocalizer(const world::FieldMap& map, const world::PinholeCamera& camera,
                const std::vector<color::LightingPrior>& priors, const RbpfConfig& config);

  /// Global localization: poses uniform over the free field, lighting filters at their priors, and
  /// the global search over the next images.
  void initUniform();
  /// Poses from N(mean, cov) (x, y, yaw); no global search.
  void initGaussian(const math::SE2& mean, const Eigen::Matrix3d& cov);

  struct StepResult {
    double effective_sample_size = 0.0;
    bool resampled = false;
    int mirrored = 0;                        // particles replaced by mirrors at the resampling
    double mean_pixel_log_likelihood = 0.0;  // per used pixel, of the average particle likelihood
    int pixels_used = 0;                     // by the best particle
    // A relocalization check or a second draw of the global search ended with this image: the
    // best search pose's summed log-likelihood minus the best particle pose's (NaN: none ended).
    double relocalization_score = std::numeric_limits<double>::quiet_NaN();
    // The relocalization check found the particles lost; global_search_restarted: the global
    // search starts again (RelocalizationConfig::restart), otherwise part of the particles were
    // drawn from the check's poses.
    bool relocalized = false;
    // A relocalization check ended with this image.
    bool relocalization_checked = false;
    bool global_search_restarted = false;
    // The global search's second draw replaced part of the particles.
    bool second_draw = false;
    // The mirror test's evidence for the mirror of the estimate after this image (0: not run) and
    // whether the particles were moved to their mirrors.
    double mirror_evidence = 0.0;
    bool mirror_flipped = false;
    // Goals seen on the first image of a global search (goal_detection.h; -1: not looked for).
    int goal_sightings = -1;
    // The body lean added to the camera pose (goal_pitch_correction).
    double camera_pitch_offset_rad = 0.0;
  };
  /// One image: odometry delta since the previous image (in the previous base frame), elapsed time,
  /// the YUV image (CV_8UC3) and the camera pose on the robot (base_link -> camera_optical_frame;
  /// the goal_pitch_correction's lean is added to it).
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
  /// True from initUniform() until step() has scored global.search_frames images on the pool.
  bool globalSearchPending() const { return global_.searching(); }

  const std::vector<Particle>& particles() const { return particles_; }
  const std::vector<double>& weights() const { return weights_; }
  using PoseEstimate = localization::PoseEstimate;
  /// The pose estimate: the main cluster's weighted mean (pose_cluster.h).
  PoseEstimate estimate() const;
  /// The particle with the highest weight.
  const Particle& best() const;
  const RbpfConfig& config() const { return config_; }
  /// The white balance the images are read under (identity until one is taken: balance_to_paint).
  const color::WhiteBalance& whiteBalance() const { return balance_; }
  const std::vector<world::PixelCoord>& pixels() const { return image_.pixels; }

 private:
  void weighParticle(size_t i, const math::SE2& odom_delta, double dt_s,
                     const Eigen::Isometry3d& base_to_optical, std::uint64_t frame_seed);
  /// Forgets the searches and the mirror test (the particles were placed anew).
  void resetSearches();
  /// Resamples (with mirrors, see mirror_fraction).
  void resample(StepResult* result);
  /// Settles a finished contest (a relocalization check's or the second draw's) and applies it:
  /// when the search's best pose beats the particles' by `margin` and fraction > 0, either
  /// restarts the global search (`restart`) or draws `fraction` of the particles from the search's
  /// poses with `lighting` (the rest kept, drawn by weight). Returns whether it redrew.
  bool applyContest(PoseContest contest, const color::SwitchingColorFilter& lighting,
                    std::uint64_t frame_seed, double margin, double fraction, bool restart,
                    int refine_candidates, StepResult* result);
  std::vector<math::SE2> poses() const;
  /// A lighting filter at the priors (the particles' start, and the searches' lighting).
  const color::SwitchingColorFilter& priorLighting() const { return prior_lighting_; }

  /// `count` poses drawn around the goals this image shows (goal_detection.h) and its centre
  /// circle (centre_circle.h), shared among the sightings; none on a field without either. The
  /// goal sightings go to `seen` when given.
  std::vector<math::SE2> goalProposals(const cv::Mat& yuv, const Eigen::Isometry3d& base_to_optical,
                                       std::uint64_t frame_seed, int count,
                                       std::vector<GoalSighting>* seen = nullptr) const;
  /// When the particles were just placed (adapt_priors_to_image): the white balance taken from this
  /// image's paint (balance_to_paint) and the priors adapted to the balanced image. Returns the
  /// image balanced as every image since.
  cv::Mat adaptToImage(const cv::Mat& yuv);

  std::vector<color::LightingPrior> priors_;  // as given; adapted copies go into the filters below
  RbpfConfig config_;
  bool adapt_pending_ = false;
  color::WhiteBalance balance_;  // of the images since the particles were placed (balance_to_paint)
  int unbalanced_images_ = 0;    // images since an adaptation that gave no balance
  color::SwitchingColorFilter prior_lighting_;
  std::shared_ptr<const ImageLikelihood> likelihood_;
  PoseSearch search_;
  GlobalLocalization global_;
  RelocalizationMonitor relocalization_;
  MirrorTest mirror_test_;
  math::Rng rng_;
  std::vector<Particle> particles_;
  std::vector<double> weights_;
  SampledImage image_;  // the current image on the likelihood's grid
  Eigen::Isometry3d offsets_camera_ = Eigen::Isometry3d(Eigen::Matrix4d::Zero());  // image_'s
  std::vector<int> pixels_used_;
  std::uint64_t frame_ = 0;
  double pitch_offset_rad_ = 0.0;  // goal_pitch_correction's
};

}  // namespace adaptive_perception::localization
