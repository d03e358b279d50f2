// The field tables (config/fields.h) of ekf_slam_mapper's configs, as its parameters and
// evaluate_slam's options name them: the laser SLAM's, the data association's and the EKF's (which
// nests the motion model's, as ~odom_*). Written once, for validate(), the node, the tool and the
// doc page.
#include <stdexcept>
#include <string>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/slam/data_association.h"
#include "adaptive_perception/slam/laser_slam.h"
#include "adaptive_perception/slam/line_ekf_slam.h"

namespace adaptive_perception::slam {

const config::Fields<LaserSlamConfig>& LaserSlamConfig::fields() {
  using C = LaserSlamConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("front_end", &C::front_end,
               "predict the EKF from laser odometry (scan matching); false: from wheel odometry")
          .add("loop_closing", &C::loop_closing,
               "a pose graph with loop edges over the EKF's keyframes")
          .add("wide_search", &C::loop, &LoopClosingConfig::wide_search,
               "loops beyond the local window found by branch and bound (LoopClosingConfig)")
          .nest(&C::ekf, LineEkfSlamConfig::fields());
  return f;
}

const config::Fields<DataAssociationConfig>& DataAssociationConfig::fields() {
  using C = DataAssociationConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("gate_probability", &C::gate_probability, config::closed(0.5, 0.999999),
               "chi-square gate of individual and joint compatibility (probability)")
          .add("share_landmarks", &C::share_landmarks,
               "segments of one wall update one landmark together");
  return f;
}

const config::Fields<LineEkfSlamConfig>& LineEkfSlamConfig::fields() {
  using C = LineEkfSlamConfig;
  using config::closed;
  static const config::Fields<C> f =
      config::Fields<C>()
          .nest(&C::association, DataAssociationConfig::fields())
          .add("confirm_sightings", &C::confirm_sightings, closed(1, 1000),
               "sightings that confirm a landmark")
          .add("tentative_timeout_scans", &C::tentative_timeout_scans, closed(1, 100000),
               "an unconfirmed landmark unseen this many scans is dropped")
          .add("min_new_line_length_m", &C::min_new_line_length_m, closed(0, 100),
               "shorter segments update landmarks but never start one (m)")
          .add("line_model_rho_std_m", &C::line_model_rho_std_m, closed(0, 10),
               "how far a wall departs from a straight line, added to every observation (m)")
          .add("line_model_alpha_std_rad", &C::line_model_alpha_std_rad, closed(0, 1),
               "the same for the wall's direction (rad)")
          .add("anchor_min_angle_rad", &C::anchor_min_angle_rad, closed(0, math::kPi / 2),
               "anchor variant: the second anchor's direction differs from the first by this "
               "(rad)")
          .add("retire_after_updates", &C::retire_after_updates, closed(0, 1000000),
               "a landmark updated this often leaves the state (0: never; the paper used 50)")
          .add("merge_landmarks", &C::merge_landmarks,
               "two landmarks that become one wall are merged")
          .add("first_estimate_jacobians", &C::first_estimate_jacobians,
               "linearise each landmark at its first estimate (FEJ-EKF)")
          .nest(&C::motion, localization::MotionModelConfig::fields());
  return f;
}

void LineEkfSlamConfig::validate() const {
  fields().validate(*this);
  association.validate();
}

}  // namespace adaptive_perception::slam
