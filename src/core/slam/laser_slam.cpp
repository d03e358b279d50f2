#include "adaptive_perception/slam/laser_slam.h"

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

LaserSlam::LaserSlam(const LaserSlamConfig& config, const math::SE2& start,
                     const Eigen::Matrix3d& start_cov)
    : config_(config),
      front_end_(config.laser_odometry),
      ekf_(ekfConfig(config), start, start_cov),
      loop_(config.loop) {}

LaserSlam::Step LaserSlam::add(const std::vector<Eigen::Vector2d>& points_robot,
                               const std::vector<LineObservation>& lines, const math::SE2& odom,
                               const ExternalPosition* external) {
  Step step;
  step.prediction = config_.front_end ? front_end_.add(points_robot, odom) : odom;
  ekf_.predictFromOdometry(step.prediction);
  step.ekf = ekf_.update(lines);
  if (external) ekf_.updateExternalPosition(external->xy_m, external->cov);
  if (config_.loop_closing)
    loop_.add(points_robot, ekf_.pose(), config_.front_end ? &step.prediction : nullptr);
  else
    ekf_poses_.push_back(ekf_.pose());
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
