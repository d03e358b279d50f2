#pragma once
// Data association of two-row observations (a line's (rho, alpha)) with the landmarks of an EKF
// state. First individual compatibility: a pairing is a candidate when the squared Mahalanobis
// distance of its innovation is within the chi-square gate at gate_probability (2 dof). Then
// either the nearest candidate (kNearestNeighbour) or joint compatibility branch and bound (kJcbb,
// Neira & Tardos 2001): the largest set of pairings whose stacked innovation is jointly within the
// gate (2 dof per pairing), the smallest joint distance among sets of that size.
//
// The filter supplies each pairing linearised (LinearPairing) and its state covariance; nothing
// here knows what a landmark is. JCBB grows the Cholesky factor of the joint innovation
// covariance by two rows per pairing, so a node of its search costs O(m^2) for m pairings.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/config/fields.h"

namespace adaptive_perception::slam {

enum class Association { kNearestNeighbour, kJcbb };
/// "nn" | "jcbb"; throws std::invalid_argument naming the allowed values.
/// The association methods' words: "nn", "jcbb".
const config::EnumNames<Association>& associations();
Association parseAssociation(const std::string& name);
std::string associationName(Association a);  // "nn" | "jcbb"

struct DataAssociationConfig {
  Association method = Association::kJcbb;
  double gate_probability = 0.99;  // chi-square gate of individual and joint compatibility
  // Several observations of one scan may pair with the same landmark (JCBB; nearest neighbour
  // always allows it): a wall broken by a doorway, an alcove or an occluder is one line and its
  // pieces are independent measurements of it. Without this, JCBB's one-to-one pairing makes
  // every extra piece a new landmark that is merged back after confirmation, over and over
  // (hundreds of merges in a 2-minute loop), and the pose NEES of the simulator loop came out
  // over-confident on 3 of 20 held-out seeds (mean NEES 5.6 to 6.0).
  bool share_landmarks = true;
  // JCBB search budget per scan (tree nodes); past it the best hypothesis found so far is used.
  long jcbb_max_nodes = 20000;
  /// gate_probability and share_landmarks (config/fields.h); method is an enum
  /// (parseAssociation).
  static const config::Fields<DataAssociationConfig>& fields();
  void validate() const;  // throws std::invalid_argument naming the first field out of range
};

/// One observation paired with one landmark, linearised: innovation nu = z - h(x), measurement
/// Jacobian H = [hr at the pose's state columns 0..2, hl at columns col and col + 1], noise r.
/// col < 0: a landmark outside the state (fixed), whose own uncertainty r already holds.
struct LinearPairing {
  Eigen::Vector2d nu;
  Eigen::Matrix<double, 2, 3> hr;
  Eigen::Matrix2d hl, r;
  int col = -1;
};

class DataAssociation {
 public:
  /// Throws std::invalid_argument (DataAssociationConfig::validate).
  explicit DataAssociation(DataAssociationConfig config);

  /// The pairing of observation `obs` with landmark `lm`, linearised at the current state.
  using Linearise = std::function<LinearPairing(int obs, int lm)>;
  /// Per observation (0 .. observations - 1) the landmark (0 .. landmarks - 1) it pairs with, or
  /// -1 (a new or spurious observation). `p` is the state covariance, the pose in rows 0..2.
  std::vector<int> associate(int observations, int landmarks, const Eigen::MatrixXd& p,
                             const Linearise& linearise) const;
  /// Squared Mahalanobis distance of one pairing: nu^T S^-1 nu with S = H P H^T + r.
  static double mahalanobis(const LinearPairing& q, const Eigen::MatrixXd& p);
  /// The chi-square quantile of gate_probability at `dof` degrees of freedom (cached).
  double gate(int dof) const;
  const DataAssociationConfig& config() const { return config_; }

 private:
  struct Pairing {
    int obs, lm;
  };
  struct Branch;
  void jcbb(const std::vector<std::vector<int>>& candidates, const Eigen::MatrixXd& p,
            const Linearise& linearise, size_t i, Branch& branch, std::vector<Pairing>& best,
            double& best_d2, long& nodes) const;

  DataAssociationConfig config_;
  mutable std::vector<double> gate_by_dof_;
};

}  // namespace adaptive_perception::slam
