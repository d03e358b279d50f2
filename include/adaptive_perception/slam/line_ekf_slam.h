#pragma once
// EKF SLAM with line landmarks (Garulli et al. 2005, section 2.2): the state is the robot pose
// (x, y, theta) in map followed by the landmarks (rho, alpha); see line_landmark_model.h for the
// models. Per scan:
//   1. predict(): pose composed with the odometry delta, covariance F_x P F_x^T + F_v Q F_v^T on
//      the pose rows and columns only (O(n));
//   2. update(): data association of the scan's lines with the landmarks (data_association.h:
//      individual compatibility, then nearest neighbour or JCBB); one stacked update with gain eq.
//      7, innovation eq. 8 and the Joseph-form covariance of eq. 9, evaluated in O(n^2 m) by
//      expanding the product; new landmarks added with their full cross-covariance (G_r P G_r^T +
//      G_z R G_z^T);
//   Optionally with first-estimates Jacobians (first_estimate_jacobians).
//   3. tentative landmarks (seen fewer than confirm_sightings times) that go unseen for
//      tentative_timeout_scans scans are removed.
//
// Fully observable variants (section 2.2, eqs. 19-27):
//   - kStandard: the plain filter; its map is only known relative to the first observations.
//   - kAnchor: confirmed landmarks fix the map frame (eqs. 20-22, 24-25), the line counterpart of
//     the paper's point anchor. A line fixes two of the frame's three degrees of freedom, so: the
//     first confirmed landmark becomes a fixed global reference (the state is conditioned on its
//     current estimate, the map frame is redefined by it, and it leaves the state; its
//     observations keep correcting the pose with H = [H_r 0]); then the first confirmed one at
//     least anchor_min_angle_rad away in direction fixes the third, the position of its
//     intersection with the first along it (a rank-one conditioning; the line stays in the state,
//     Landmark::gauge). Fixing the second line whole would over-constrain the frame: its angle to
//     the first would be asserted exact.
//   - kExternal: an absolute pose sensor (eqs. 23, 26-27) through updateExternalPosition() /
//     updateExternalPose().
//   Retirement (any variant, retire_after_updates > 0): a landmark revised more than that many
//   times leaves the state (marginalised: its last estimate and marginal covariance are kept), but
//   its observations still correct the pose, with the landmark covariance added to the measurement
//   noise (the paper's USC SAL run used 50).
//
// Landmark indices: 0 .. numLandmarks()-1 are the landmarks in the state; numLandmarks() ..
// numLandmarks()+numFixedLandmarks()-1 the fixed (anchored or retired) ones, as returned by
// associate().
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/laser/line_extraction.h"
#include "adaptive_perception/localization/motion_model.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/slam/data_association.h"
#include "adaptive_perception/slam/line_landmark_model.h"

namespace adaptive_perception::slam {

enum class Variant { kStandard, kAnchor, kExternal };
/// "standard" | "anchor" | "external"; throws std::invalid_argument naming the allowed values.
/// The variants' words: "standard", "anchor", "external".
const config::EnumNames<Variant>& variants();
Variant parseVariant(const std::string& name);
std::string variantName(Variant v);

struct LineEkfSlamConfig {
  DataAssociationConfig association;   // gate, nearest neighbour or JCBB, shared landmarks
  int confirm_sightings = 3;           // a landmark is confirmed after this many sightings
  int tentative_timeout_scans = 10;    // unconfirmed landmarks unseen this long are dropped
  double min_new_line_length_m = 0.5;  // shorter segments update but never start a landmark
  // Model error added to each line's fit covariance: the fit covariance only knows range noise,
  // not segmentation, corners, beam divergence or scans taken on the move, and successive scans'
  // errors are not independent; a wall split into pieces is also seen twice in one scan. Chosen
  // on simulator seeds 1-10 of the loop world (scripts/evaluate_slam_consistency.sh): 0.01 m /
  // 0.005 rad gave a mean pose NEES of 5.0 (over-confident), 0.02 m / 0.01 rad 2.2.
  double line_model_rho_std_m = 0.02;
  double line_model_alpha_std_rad = 0.01;
  // Odometry noise per step, amcl-style (localization/motion_model.h): sd(dx, dy) = a3 |t| +
  // a4 |r| + min_t, sd(dtheta) = a1 |r| + a2 |t| + min_r. Lower than a particle filter's defaults:
  // the EKF wants the real noise, not the spread that keeps a particle set diverse.
  localization::MotionModelConfig motion{0.1, 0.05, 0.08, 0.01, 0.001, 0.001};
  Variant variant = Variant::kStandard;
  double anchor_min_angle_rad = 0.5;  // direction difference of the second anchor to the first
  int retire_after_updates = 0;       // 0: retirement off; the paper used 50
  // Two landmarks whose difference is compatible with zero at association.gate_probability are
  // merged (the
  // same wall initialised twice before a loop closed); checked for the landmarks seen each scan.
  bool merge_landmarks = true;
  // false: no landmark is started, the filter localizes against the landmarks it has (a map loaded
  // with addFixedLandmarks: ekf_slam_mapper's ~initial_map).
  bool extend_map = true;
  // First-estimates Jacobians (FEJ-EKF; Huang, Mourikis & Roumeliotis 2008): the motion Jacobian
  // uses the predicted positions x_{k+1|k} - x_{k|k-1} and the observation Jacobians the predicted
  // pose x_{k|k-1} and each landmark's first direction estimate, so the linearised filter keeps
  // the three unobservable directions of the standard model (global translation and rotation)
  // unobservable (the plain EKF, linearised at the latest estimates, gains heading information
  // that does not exist; see the FirstEstimatesJacobiansKeepTheHeadingUnobservable test). Means
  // and innovations always use the latest estimates. Off by default: on the simulator loop (seeds
  // 11-30) it lowered the share of scans with the pose NEES in bounds from 0.896 to 0.822 and
  // raised the ATE from 0.073 to 0.081 m; a line first seen as a short far segment has a poor
  // first direction, and the Jacobians stay there.
  bool first_estimate_jacobians = false;
  /// The tunable fields (config/fields.h; the data association's and the motion model's, as
  /// ~odom_*), the association method and the variant aside (enums: parseAssociation,
  /// parseVariant). Defined in slam_configs.cpp.
  static const config::Fields<LineEkfSlamConfig>& fields();
  void validate() const;  // throws std::invalid_argument naming the first field out of range
};

struct Landmark {
  std::uint64_t id = 0;
  int sightings = 0;
  int last_seen_scan = 0;
  // Extent along the line for display: endpoints in map, the union of every matched segment, and
  // the pieces of wall actually seen (segments closer than kPieceGapM are joined): collinear walls
  // are one landmark in the line model but several pieces on screen.
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero(), end_m = Eigen::Vector2d::Zero();
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> pieces;
  static constexpr double kPieceGapM = 0.5;
  bool confirmed() const { return confirmed_flag; }
  bool confirmed_flag = false;
  double first_alpha_rad = 0.0;  // direction at initialisation: the FEJ linearisation point
  // Anchor variant: the second reference line. Its intersection with the first anchor, along
  // that line, is fixed (zero variance); the line itself stays in the state.
  bool gauge = false;
};

/// A landmark outside the state: an anchor (zero covariance, defines the map frame) or a retired
/// landmark (its marginal covariance at retirement).
struct FixedLandmark {
  Landmark info;
  Line line;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  bool anchor = false;
};

struct LineObservation {
  Line line;                       // in the robot frame
  Eigen::Matrix2d cov;             // of (rho, alpha)
  Eigen::Vector2d start_m, end_m;  // segment endpoints in the robot frame
};

/// Segments extracted in the laser frame as observations in the robot (base) frame, with the
/// covariance carried through the mount transform.
std::vector<LineObservation> toObservations(const std::vector<laser::LineSegment>& segments,
                                            const math::SE2& laser_in_base);

class LineEkfSlam {
 public:
  static constexpr int kPoseDim = 3;
  static constexpr int kLandmarkDim = 2;
  /// State index of landmark i's rho (alpha follows).
  static int landmarkIndex(int i) { return kPoseDim + kLandmarkDim * i; }

  explicit LineEkfSlam(const LineEkfSlamConfig& config = LineEkfSlamConfig(),
                       const math::SE2& start = math::SE2(),
                       const Eigen::Matrix3d& start_cov = Eigen::Matrix3d::Zero());

  /// Prediction from an odometry pose (odom -> base): the delta since the previous call; the first
  /// call only records it. Returns false (and predicts nothing) on that first call.
  bool predictFromOdometry(const math::SE2& odom_pose);
  /// Odometry delta in the previous robot frame.
  void predict(const math::SE2& odom_delta);
  void predict(const math::SE2& odom_delta, const Eigen::Matrix3d& delta_cov);

  struct UpdateResult {
    int matched = 0, added = 0, removed = 0, anchored = 0, retired = 0, merged = 0;
    std::vector<int> association;  // per observation: landmark index or -1
    // Normalised innovation squared of the stacked update and its degrees of freedom (2 per
    // matched line; 0 when nothing matched): chi-square with nis_dof degrees when the filter is
    // consistent, a check that needs no ground truth.
    double nis = 0.0;
    int nis_dof = 0;
  };
  UpdateResult update(const std::vector<LineObservation>& observations);

  /// Landmarks of a known map (slam/map_io.h readLineMap), outside the state: their observations
  /// correct the pose with each landmark's covariance added to the measurement noise, as retired
  /// ones do; they are never revised. Throws std::invalid_argument on a non-finite line or a
  /// covariance that is not symmetric positive semi-definite.
  void addFixedLandmarks(const std::vector<FixedLandmark>& landmarks);

  /// Data association alone (for tests and tools): per observation a landmark index or -1.
  std::vector<int> associate(const std::vector<LineObservation>& observations) const;

  /// External absolute sensor (eqs. 26-27): the robot position (x, y) in map, or the full pose
  /// (x, y, yaw), with its covariance. Joseph-form update; returns the squared Mahalanobis distance
  /// of the innovation (the caller may gate on it).
  double updateExternalPosition(const Eigen::Vector2d& xy_m, const Eigen::Matrix2d& cov);
  double updateExternalPose(const math::SE2& pose, const Eigen::Matrix3d& cov);

  math::SE2 pose() const { return math::SE2(x_[0], x_[1], x_[2]); }
  Eigen::Matrix3d poseCovariance() const { return p_.topLeftCorner<3, 3>(); }
  int numLandmarks() const { return static_cast<int>(landmarks_.size()); }
  Line landmark(int i) const { return Line{x_[landmarkIndex(i)], x_[landmarkIndex(i) + 1]}; }
  Eigen::Matrix2d landmarkCovariance(int i) const {
    return p_.block<2, 2>(landmarkIndex(i), landmarkIndex(i));
  }
  const Landmark& landmarkInfo(int i) const { return landmarks_[i]; }
  int numFixedLandmarks() const { return static_cast<int>(fixed_.size()); }
  const FixedLandmark& fixedLandmark(int k) const { return fixed_[k]; }
  const Eigen::VectorXd& state() const { return x_; }
  const Eigen::MatrixXd& covariance() const { return p_; }
  const LineEkfSlamConfig& config() const { return config_; }
  Eigen::Matrix3d odometryNoise(const math::SE2& delta) const;

 private:
  struct Pairing {
    int obs, lm;
  };
  /// One block of measurement rows in sparse form: z - h = nu, H = [hr at the pose columns,
  /// hl at columns col..col+1 (none when col < 0)], noise r.
  struct Block {
    Eigen::VectorXd nu;
    Eigen::MatrixXd hr, hl, r;
    int col = -1;
    Eigen::MatrixXd hl2;  // a second landmark (merging), at col2 when col2 >= 0
    int col2 = -1;
  };
  Eigen::Matrix2d modelNoise() const;
  /// Innovation z - h of obs against landmark lm (state index, or fixed after them), with the
  /// Jacobians (first estimates when configured) and the measurement noise (with a fixed
  /// landmark's own covariance folded in).
  Eigen::Vector2d linearise(const LineObservation& obs, int lm, Eigen::Matrix<double, 2, 3>* hr,
                            Eigen::Matrix2d* hl, Eigen::Matrix2d* r) const;
  Block pairingBlock(const LineObservation& obs, int lm) const;
  /// The pairing of obs with landmark lm, linearised for the data association.
  LinearPairing linearPairing(const LineObservation& obs, int lm) const;
  std::vector<Block> blocks(const std::vector<LineObservation>& obs,
                            const std::vector<Pairing>& pairs) const;
  /// The stacked update (eqs. 6-9); returns the squared Mahalanobis distance of the innovation.
  double applyUpdate(const std::vector<Block>& b);
  void normaliseLandmarks();
  void anchorOrRetire(UpdateResult* res);
  /// Coordinate along `anchor` (from its foot point, along (-sin, cos) of its normal) of its
  /// intersection with l.
  static double alongFirstAnchor(const Line& anchor, const Line& l);
  /// Conditions the state on landmark j's intersection with `anchor` (the third gauge freedom).
  void fixGauge(int j, const Line& anchor);
  /// Merges landmarks compatible with one of `seen` (state indices); returns how many merged.
  int mergeCompatible(std::vector<int> seen);
  /// Moves landmark i out of the state: conditioned on its estimate (anchor) or marginalised.
  void fixLandmark(int i, bool anchor);
  void extendExtent(const Line& l, const LineObservation& obs, Landmark* lm);
  void addLandmark(const LineObservation& obs, int scan);
  void removeLandmark(int i);
  void extendExtent(int i, const LineObservation& obs);

  LineEkfSlamConfig config_;
  DataAssociation association_;
  Eigen::VectorXd x_;
  Eigen::MatrixXd p_;
  std::vector<Landmark> landmarks_;
  std::vector<FixedLandmark> fixed_;
  std::uint64_t next_id_ = 0;
  bool have_odom_ = false;
  math::SE2 last_odom_;
  // The last predicted pose x_{k|k-1} (the start pose before any prediction): where the
  // first-estimates Jacobians linearise the robot.
  math::SE2 lin_pose_;
  int scan_ = 0;
};

}  // namespace adaptive_perception::slam
