#pragma once
// EKF SLAM with line landmarks (Garulli et al. 2005, section 2.2): the state is the robot pose
// (x, y, theta) in map followed by the landmarks (rho, alpha); see line_landmark_model.h for the
// models. Per scan:
//   1. predict(): pose composed with the odometry delta, covariance F_x P F_x^T + F_v Q F_v^T on
//      the pose rows and columns only (O(n));
//   2. update(): data association of the scan's lines with the landmarks, individual compatibility
//      (chi-square gate on each pairing) then either nearest neighbour or joint compatibility
//      branch and bound (JCBB, Neira & Tardos 2001: the largest set of pairings that is jointly
//      compatible); one stacked update with gain eq. 7, innovation eq. 8 and the Joseph-form
//      covariance of eq. 9, evaluated in O(n^2 m) by expanding the product; new landmarks added
//      with their full cross-covariance (G_r P G_r^T + G_z R G_z^T);
//   3. tentative landmarks (seen fewer than confirm_sightings times) that go unseen for
//      tentative_timeout_scans scans are removed.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/slam/line_landmark_model.h"

namespace adaptive_perception::slam {

enum class Association { kNearestNeighbour, kJcbb };
/// "nn" | "jcbb"; throws std::invalid_argument naming the allowed values.
Association parseAssociation(const std::string& name);

struct LineEkfSlamConfig {
  Association association = Association::kJcbb;
  double gate_probability = 0.99;      // chi-square gate of individual and joint compatibility
  int confirm_sightings = 3;           // a landmark is confirmed after this many sightings
  int tentative_timeout_scans = 10;    // unconfirmed landmarks unseen this long are dropped
  double min_new_line_length_m = 0.5;  // shorter segments update but never start a landmark
  // Odometry noise per step (amcl-style): sd(dx, dy) = a3 |t| + a4 |r| + min_t,
  // sd(dtheta) = a1 |r| + a2 |t| + min_r.
  double alpha1 = 0.1, alpha2 = 0.05, alpha3 = 0.05, alpha4 = 0.01;
  double min_translation_std_m = 0.001, min_rotation_std_rad = 0.001;
  void validate() const;
};

struct Landmark {
  std::uint64_t id = 0;
  int sightings = 0;
  int last_seen_scan = 0;
  // Extent along the line for display: endpoints in map, the union of every matched segment.
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero(), end_m = Eigen::Vector2d::Zero();
  bool confirmed() const { return confirmed_flag; }
  bool confirmed_flag = false;
};

struct LineObservation {
  Line line;                       // in the robot frame
  Eigen::Matrix2d cov;             // of (rho, alpha)
  Eigen::Vector2d start_m, end_m;  // segment endpoints in the robot frame
};

class LineEkfSlam {
 public:
  static constexpr int kPoseDim = 3;
  static constexpr int kLandmarkDim = 2;
  /// State index of landmark i's rho (alpha follows).
  static int landmarkIndex(int i) { return kPoseDim + kLandmarkDim * i; }

  explicit LineEkfSlam(const LineEkfSlamConfig& config = LineEkfSlamConfig(),
                       const math::SE2& start = math::SE2(),
                       const Eigen::Matrix3d& start_cov = Eigen::Matrix3d::Zero());

  /// Odometry delta in the previous robot frame.
  void predict(const math::SE2& odom_delta);
  void predict(const math::SE2& odom_delta, const Eigen::Matrix3d& delta_cov);

  struct UpdateResult {
    int matched = 0, added = 0, removed = 0;
    std::vector<int> association;  // per observation: landmark index or -1
  };
  UpdateResult update(const std::vector<LineObservation>& observations);

  /// Data association alone (for tests and tools): per observation a landmark index or -1.
  std::vector<int> associate(const std::vector<LineObservation>& observations) const;

  math::SE2 pose() const { return math::SE2(x_[0], x_[1], x_[2]); }
  Eigen::Matrix3d poseCovariance() const { return p_.topLeftCorner<3, 3>(); }
  int numLandmarks() const { return static_cast<int>(landmarks_.size()); }
  Line landmark(int i) const { return Line{x_[landmarkIndex(i)], x_[landmarkIndex(i) + 1]}; }
  Eigen::Matrix2d landmarkCovariance(int i) const {
    return p_.block<2, 2>(landmarkIndex(i), landmarkIndex(i));
  }
  const Landmark& landmarkInfo(int i) const { return landmarks_[i]; }
  const Eigen::VectorXd& state() const { return x_; }
  const Eigen::MatrixXd& covariance() const { return p_; }
  const LineEkfSlamConfig& config() const { return config_; }
  Eigen::Matrix3d odometryNoise(const math::SE2& delta) const;

 private:
  struct Pairing {
    int obs, lm;
  };
  /// Stacked innovation and Jacobian of a set of pairings.
  void stack(const std::vector<LineObservation>& obs, const std::vector<Pairing>& pairs,
             Eigen::VectorXd* nu, Eigen::MatrixXd* h, Eigen::MatrixXd* r) const;
  double jointMahalanobis(const std::vector<LineObservation>& obs,
                          const std::vector<Pairing>& pairs) const;
  void jcbb(const std::vector<LineObservation>& obs,
            const std::vector<std::vector<int>>& candidates, size_t i,
            std::vector<Pairing>& current, std::vector<Pairing>& best, double& best_d2,
            long& nodes) const;
  void addLandmark(const LineObservation& obs, int scan);
  void removeLandmark(int i);
  void extendExtent(int i, const LineObservation& obs);

  LineEkfSlamConfig config_;
  Eigen::VectorXd x_;
  Eigen::MatrixXd p_;
  std::vector<Landmark> landmarks_;
  std::uint64_t next_id_ = 0;
  int scan_ = 0;
};

}  // namespace adaptive_perception::slam
