// evaluate_slam: line extraction + line-landmark EKF SLAM offline over a laser bag (simulator or a
// converted CARMEN log), against ground_truth/pose when the bag has it.
//
//   evaluate_slam --bag FILE [--association jcbb|nn] [--gate_probability 0.99] [--output DIR]
//
// Odometry: nav_msgs/Odometry on `odom`, the message nearest each scan; base_link -> laser from
// /tf_static (identity when absent). Summary keys (last line):
//   evaluate_slam: ate_m=.. final_position_error_m=.. odometry_final_position_error_m=..
//       nees_in_bounds=.. landmarks=.. scans=.. realtime_factor=..
// ate_m: RMS position error over the scans (no alignment: the map frame starts at the first true
// pose). nees_in_bounds: share of scans whose pose NEES lies inside the 95% chi-square interval of
// 3 degrees of freedom. Both -1 without ground truth. Writes OUTPUT/estimate.tum, truth.tum,
// landmarks.csv (rho, alpha, endpoints, sightings).
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "adaptive_perception/laser/line_extraction.h"
#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/chi_square.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/slam/line_ekf_slam.h"
#include "adaptive_perception/world/camera_model.h"
#include "tool_args.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;

namespace {
template <typename T>
const T* nearest(const std::map<ros::Time, T>& m, const ros::Time& t) {
  if (m.empty()) return nullptr;
  auto it = m.lower_bound(t);
  if (it == m.end()) return &std::prev(it)->second;
  if (it != m.begin() && (t - std::prev(it)->first) < (it->first - t)) --it;
  return &it->second;
}
void tum(std::ofstream& f, double t, const math::SE2& p) {
  f << std::fixed << t << " " << p.x_m << " " << p.y_m << " 0 0 0 " << std::sin(0.5 * p.yaw_rad)
    << " " << std::cos(0.5 * p.yaw_rad) << "\n";
}
}  // namespace

int main(int argc, char** argv) {
  tools::Args args(argc, argv,
                   "evaluate_slam --bag FILE [--association jcbb|nn] [--gate_probability P] "
                   "[--output DIR]");
  const std::string bag_path = args.get("bag", "");
  slam::LineEkfSlamConfig cfg;
  const std::string association = args.get("association", "jcbb");
  cfg.gate_probability = args.getDouble("gate_probability", cfg.gate_probability);
  const std::string output = args.get("output", "results/evaluate_slam");
  args.finish();
  if (bag_path.empty()) args.fail("--bag FILE is required");
  try {
    cfg.association = slam::parseAssociation(association);
    cfg.validate();
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    std::vector<sensor_msgs::LaserScanConstPtr> scans;
    std::map<ros::Time, math::SE2> odom, truth;
    math::SE2 mount;
    for (const auto& m : rosbag::View(bag)) {
      if (auto s = m.instantiate<sensor_msgs::LaserScan>()) {
        scans.push_back(s);
      } else if (auto o = m.instantiate<nav_msgs::Odometry>()) {
        odom[o->header.stamp] = ros_conv::toSE2(o->pose.pose);
      } else if (auto g = m.instantiate<geometry_msgs::PoseStamped>()) {
        if (m.getTopic() == ros_topics::kGroundTruthPose ||
            m.getTopic() == std::string("/") + ros_topics::kGroundTruthPose)
          truth[g->header.stamp] = ros_conv::toSE2(g->pose);
      } else if (auto tf = m.instantiate<tf2_msgs::TFMessage>()) {
        if (m.getTopic() == "/tf_static")
          for (const auto& t : tf->transforms)
            if (t.child_frame_id == ros_topics::kLaserFrame)
              mount = world::isometryToPlanar(ros_conv::toIsometry(t.transform));
      }
    }
    if (scans.empty()) throw std::runtime_error(bag_path + ": no sensor_msgs/LaserScan messages");
    if (odom.empty()) throw std::runtime_error(bag_path + ": no nav_msgs/Odometry on odom");
    const math::SE2* t0 = nearest(truth, scans.front()->header.stamp);
    slam::LineEkfSlam ekf(cfg, t0 ? *t0 : math::SE2());
    laser::LineExtractor extractor;
    fs::create_directories(output);
    std::ofstream est_tum(fs::path(output) / "estimate.tum"),
        truth_tum(fs::path(output) / "truth.tum");
    const double nees_lo = math::chiSquareQuantile(0.025, 3),
                 nees_hi = math::chiSquareQuantile(0.975, 3);
    double sq = 0.0, final_err = -1.0, compute_s = 0.0, odom_final_err = -1.0;
    math::SE2 dead_reckoning = ekf.pose();  // odometry alone, from the same start
    long with_truth = 0, in_bounds = 0;
    const math::SE2* prev_odom = nullptr;
    for (const auto& s : scans) {
      const math::SE2* o = nearest(odom, s->header.stamp);
      const auto c0 = std::chrono::steady_clock::now();
      if (prev_odom) {
        ekf.predict(math::between(*prev_odom, *o));
        dead_reckoning = dead_reckoning * math::between(*prev_odom, *o);
      }
      prev_odom = o;
      std::vector<slam::LineObservation> obs;
      for (const auto& seg : extractor.extract(ros_conv::fromLaserScan(*s))) {
        Eigen::Matrix2d gz;
        slam::LineObservation ob;
        ob.line =
            slam::lineToMap(mount, slam::Line{seg.line.rho_m, seg.line.alpha_rad}, nullptr, &gz);
        ob.cov = gz * seg.line.cov * gz.transpose();
        const double c = std::cos(mount.yaw_rad), sn = std::sin(mount.yaw_rad);
        auto to_base = [&](const Eigen::Vector2d& p) {
          return Eigen::Vector2d(mount.x_m + c * p.x() - sn * p.y(),
                                 mount.y_m + sn * p.x() + c * p.y());
        };
        ob.start_m = to_base(seg.start_m);
        ob.end_m = to_base(seg.end_m);
        obs.push_back(ob);
      }
      ekf.update(obs);
      compute_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
      const double t = s->header.stamp.toSec();
      tum(est_tum, t, ekf.pose());
      if (const math::SE2* g = nearest(truth, s->header.stamp)) {
        tum(truth_tum, t, *g);
        const Eigen::Vector3d e(ekf.pose().x_m - g->x_m, ekf.pose().y_m - g->y_m,
                                math::angleDiff(ekf.pose().yaw_rad, g->yaw_rad));
        sq += e.head<2>().squaredNorm();
        final_err = e.head<2>().norm();
        odom_final_err = std::hypot(dead_reckoning.x_m - g->x_m, dead_reckoning.y_m - g->y_m);
        const double nees = e.dot(ekf.poseCovariance().ldlt().solve(e));
        ++with_truth;
        in_bounds += nees >= nees_lo && nees <= nees_hi;
      }
    }
    std::ofstream lm(fs::path(output) / "landmarks.csv");
    lm << "rho_m,alpha_rad,x0,y0,x1,y1,sightings\n";
    for (int i = 0; i < ekf.numLandmarks(); ++i) {
      const auto& info = ekf.landmarkInfo(i);
      lm << ekf.landmark(i).rho_m << "," << ekf.landmark(i).alpha_rad << "," << info.start_m.x()
         << "," << info.start_m.y() << "," << info.end_m.x() << "," << info.end_m.y() << ","
         << info.sightings << "\n";
    }
    const double duration = (scans.back()->header.stamp - scans.front()->header.stamp).toSec();
    std::printf(
        "evaluate_slam: ate_m=%.3f final_position_error_m=%.3f "
        "odometry_final_position_error_m=%.3f "
        "nees_in_bounds=%.3f landmarks=%d scans=%zu realtime_factor=%.1f\n",
        with_truth ? std::sqrt(sq / with_truth) : -1.0, final_err, odom_final_err,
        with_truth ? double(in_bounds) / with_truth : -1.0, ekf.numLandmarks(), scans.size(),
        duration / std::max(compute_s, 1e-9));
  } catch (const std::exception& e) {
    std::cerr << "evaluate_slam: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
