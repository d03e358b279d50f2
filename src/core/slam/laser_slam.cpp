#include "adaptive_perception/slam/laser_slam.h"

#include <Eigen/LU>
#include <stdexcept>
#include <string>

namespace adaptive_perception::slam {

void LaserSlamConfig::validate() const {
  try {
    laser_odometry.validate();
    front_end_motion.validate();
    ekf.validate();
    loop.validate();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("LaserSlamConfig: ") + e.what());
  }
}

LineEkfSlamConfig LaserSlam::ekfConfig(const LaserSlamConfig& c) {
  c.validate();
  LineEkfSlamConfig e = c.ekf;
  if (c.front_end) e.motion = c.front_end_motion;
  return e;
}

LoopClosingConfig LaserSlam::loopConfig(const LaserSlamConfig& c) {
  LoopClosingConfig l = c.loop;
  l.chain_noise = ekfConfig(c).motion;
  return l;
}

LaserSlam::LaserSlam(const LaserSlamConfig& config, const math::SE2& start,
                     const Eigen::Matrix3d& start_cov)
    : config_(config),
      front_end_(config.laser_odometry),
      ekf_(ekfConfig(config), start, start_cov),
      loop_(loopConfig(config)) {}

LaserSlam::Step LaserSlam::add(const std::vector<Eigen::Vector2d>& points_robot,
                               const std::vector<LineObservation>& lines, const math::SE2& odom,
                               const ExternalPosition* external) {
  Step step;
  step.prediction = config_.front_end ? front_end_.add(points_robot, odom) : odom;
  ekf_.predictFromOdometry(step.prediction);
  step.ekf = ekf_.update(lines);
  if (external) ekf_.updateExternalPosition(external->xy_m, external->cov);
  if (config_.loop_closing) {
    // The front end's step covariance where its match left a direction to the odometry (its
    // information is zero before its second scan); along that direction it is the odometry's,
    // per-step floor (odom_std_*) included, which is pessimistic for a robot standing still there.
    // A step that followed the odometry because the match was not believed keeps the EKF's own
    // noise.
    Eigen::Matrix3d step_cov;
    const Eigen::Matrix3d& info = front_end_.lastInformation();
    const bool has_cov = config_.front_end && front_end_.lastMatched() &&
                         front_end_.lastDegenerateDirections() > 0 && info.trace() > 0.0;
    if (has_cov) step_cov = info.inverse();
    loop_.add(points_robot, ekf_.pose(), config_.front_end ? &step.prediction : nullptr,
              has_cov ? &step_cov : nullptr);
  } else {
    ekf_poses_.push_back(ekf_.pose());
  }
  ++scans_;
  return step;
}

math::SE2 LaserSlam::pose() const {
  return config_.loop_closing && loop_.nodes() > 0 ? loop_.lastPose() : ekf_.pose();
}

std::vector<math::SE2> LaserSlam::trajectory() const {
  return config_.loop_closing ? loop_.trajectory() : ekf_poses_;
}

}  // namespace adaptive_perception::slam
