#pragma once
// Appearance-based Monte Carlo localization (papers/002 section 4.2, the optional track):
// particles over (x, y, yaw) in `map`, weighted by how similar the current image is to the training
// frame nearest each particle's pose, with the paper's stability-driven re-initialisation.
//
// - Prediction: odometry deltas when given, else the training run's average step; the noise grows
//   as a particle's weight falls (section 4.2.2): sd = base sd x (1 + weight_noise_gain x (1 -
//   w / w_max)).
// - Weight: epsilon + similarity of the image to the training frame nearest the particle (a kd-tree
//   over (x, y, heading_weight_m cos yaw, heading_weight_m sin yaw) of the training poses). The
//   image's similarities come from the room classifier's indexed matcher: frames outside its
//   verified candidates count as 0.
// - Estimate: weighted mean pose; room by summed particle weight per room (a particle's room is
//   the room of the training frame nearest it).
// - Stability: over the last `stability_frames` estimates, each estimate's offset from the previous
//   one moved by the motion step (RMS in x and in y) below `stable_spread_m`, and the mean best
//   similarity, and the current one, at least `stable_min_weight`. While unstable the frame
//   is "not classified". Becoming unstable after a stable spell re-initialises the particles in a
//   circle around the last reliable pose, radius growing with the instability; unstable for
//   `full_reinit_after` frames in a row re-initialises over all training poses.
// - Unknown room: after the motion step, when at least `unknown_fraction` (25%) of the particles
//   are farther than `known_radius_m` from every training pose.
#include <Eigen/Core>
#include <deque>
#include <memory>
#include <opencv2/flann.hpp>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/places/feature_index.h"

namespace adaptive_perception::localization {

struct AppearanceMclConfig {
  int particles = 100;                // 10..100000
  double translation_noise_m = 0.05;  // per step, base sd of x and y
  double rotation_noise_rad = 0.05;   // per step, base sd of yaw
  double weight_noise_gain = 3.0;     // noise x (1 + gain (1 - w / w_max))
  double weight_epsilon = 0.01;       // floor of every particle's weight
  double heading_weight_m = 1.0;      // metres that a radian of heading difference counts as
  int stability_frames = 5;           // n estimates judged for stability
  double stable_spread_m = 0.5;       // max standard deviation of x and of y when stable
  double stable_min_weight = 0.15;    // min mean best-particle similarity when stable
  double reinit_radius_m = 1.0;       // restricted re-initialisation radius at mild instability
  double reinit_radius_gain_m = 4.0;  // + this x instability level (0..1)
  int full_reinit_after = 8;          // unstable frames in a row before a full re-initialisation
  double unknown_fraction = 0.25;     // share of particles outside the known rooms
  double known_radius_m = 1.5;        // a particle farther from every training pose is outside
  /// The fields appearance_localizer sets (config/fields.h).
  static const config::Fields<AppearanceMclConfig>& fields();
  void validate() const;              // throws std::invalid_argument naming the bad field
};

/// A training frame as the filter needs it: its pose and room (index into rooms).
struct PosedFrame {
  math::SE2 pose;
  int room = 0;
};

struct AppearanceEstimate {
  math::SE2 pose;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  int room = -1;  // by summed particle weight; -1 when not classified
  bool stable = false;
  bool unknown_room = false;
  bool reinitialized = false;  // this step
  bool full_reinit = false;
  double best_weight = 0.0;  // best particle's similarity
  std::vector<double> room_weights;
};

class AppearanceMcl {
 public:
  /// `frames` are the training frames with poses (at least one), `num_rooms` the room count.
  AppearanceMcl(std::vector<PosedFrame> frames, int num_rooms, AppearanceMclConfig config,
                std::uint64_t seed);

  /// Particles spread over the training poses (with noise): the global start.
  void initGlobal();
  /// Particles in a circle of `radius_m` around `center` (any heading).
  void initAround(const math::SE2& center, double radius_m);
  /// Particles drawn from N(`mean`, `covariance`) over (x_m, y_m, yaw_rad), headings wrapped: a
  /// pose the user gives (rviz's "2D Pose Estimate", amcl's initialpose). Throws
  /// std::invalid_argument when the covariance is not symmetric positive definite or not finite.
  void initGaussian(const math::SE2& mean, const Eigen::Matrix3d& covariance);

  /// One step: motion (odometry delta of base_link, or the training run's average step), the
  /// unknown-room check, weighting by `frame_similarity` (frame index -> similarity; frames not
  /// listed count as 0), estimation, stability and re-initialisation.
  AppearanceEstimate step(const std::optional<math::SE2>& odom_delta,
                          const std::vector<places::FrameMatch>& frame_similarity);

  const std::vector<math::SE2>& particles() const { return particles_; }
  const std::vector<double>& weights() const { return weights_; }
  /// Nearest training frame to a pose (heading-aware).
  int nearestFrame(const math::SE2& pose) const;
  /// Distance from a position to the nearest training position (metres).
  double distanceToKnown(double x_m, double y_m) const;
  const math::SE2& averageStep() const { return average_step_; }
  /// Test hooks: the particle set as given (weights uniform).
  void setParticles(std::vector<math::SE2> particles);

 private:
  void resample();
  AppearanceEstimate estimate() const;

  std::vector<PosedFrame> frames_;
  int num_rooms_;
  AppearanceMclConfig config_;
  math::Rng rng_;
  cv::Mat pose_points_, xy_points_;  // kd-tree inputs
  std::unique_ptr<cv::flann::Index> pose_index_, xy_index_;
  math::SE2 average_step_;
  std::vector<math::SE2> particles_;
  std::vector<double> weights_;     // normalised
  std::vector<double> similarity_;  // per particle, last step
  std::deque<math::SE2> recent_;    // last estimates' residuals against the motion (x, y)
  std::optional<math::SE2> last_estimate_;
  std::deque<double> recent_best_;     // last best similarities
  std::optional<math::SE2> reliable_;  // last estimate while stable
  int unstable_run_ = 0;
};

}  // namespace adaptive_perception::localization
