#pragma once
// The monobot of Garulli et al. 2005 (section 2.2, Figs. 4-6): a robot on a line, x_{k+1} = x_k +
// u_k + v_k (eq. 19), observing landmarks on the same line, z = x_f - x_r + w. Three measurement
// models (the variants of the line-landmark filter, slam::Variant):
//   kStandard: z = [-1 I] x + w                          fully correlated, unobservable
//   kAnchor:   z0 = anchor - x_r + w0 (eq. 20), z = ...   one known global reference
//   kExternal: z0 = x_r + w0 (eq. 23), z = ...            an external sensor on the robot
// The state is (x_r, x_f1 .. x_fn); the landmarks are initialised from the first observation with
// full cross-covariance. The robot follows a temporal sinusoid from start_m and back in `steps`
// steps; plant noise is proportional to the motion and measurement noise to the distance.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/slam/line_ekf_slam.h"  // Variant

namespace adaptive_perception::slam {

struct MonobotConfig {
  int steps = 100;            // iterations of the sinusoidal path (back at start_m)
  double start_m = -1.0;      // start estimate; the true start is off by N(0, initial_robot_std_m)
  double amplitude_m = 0.75;  // the robot reaches start_m + 2 amplitude_m at mid-path
  double initial_robot_std_m = 0.1;  // the paper uses P_r,0|0 > 0 (Fig. 3: 1)
  int landmarks = 1;                 // all at landmark_m, as in the paper
  double landmark_m = 1.0;
  double anchor_m = 0.0;               // the global reference of kAnchor, at the world origin
  double motion_noise_fraction = 0.1;  // sd(v) = fraction |u| + min_motion_std_m
  double min_motion_std_m = 0.002;
  double range_noise_fraction = 0.05;  // sd(w) = fraction distance + min_range_std_m
  double min_range_std_m = 0.01;
  double external_std_m = 0.05;  // sd of the external robot-position sensor
  void validate() const;         // throws std::invalid_argument naming the bad field
};

struct MonobotStep {
  double true_robot_m = 0.0, est_robot_m = 0.0, robot_var = 0.0;
  double measurement_m = 0.0;                       // z of landmark 1 (its range from the robot)
  double est_landmark_m = 0.0, landmark_var = 0.0;  // landmark 1
  double robot_gain = 0.0, landmark_gain = 0.0;     // K entries applied to landmark 1's innovation
};

struct MonobotRun {
  std::vector<MonobotStep> steps;          // steps[0] is the initialisation (first observation)
  Eigen::MatrixXd fisher;                  // eq. 14 summed over the run, at the true states
  double first_observation_error_m = 0.0;  // landmark 1's error right after initialisation
  double initial_robot_error_m = 0.0;      // true start - start_m: the unobservable offset
};

/// One run; deterministic for the state of `rng`.
MonobotRun runMonobot(const MonobotConfig& config, Variant model, math::Rng& rng);

}  // namespace adaptive_perception::slam
