// evaluate_slam: line extraction + line-landmark EKF SLAM offline over a laser bag (simulator or a
// converted CARMEN log), against ground_truth/pose when the bag has it.
//
//   evaluate_slam --help   (every option with its default, unit and range)
// The mapper's and the extractor's parameters are their config tables' fields, with the nodes'
// names and ranges (slam::LaserSlamConfig::fields(), laser::LineExtractionConfig::fields(); the
// tables in docs/nodes/ekf_slam_mapper.md and line_extractor.md), e.g. --front_end 0,
// --loop_closing 0, --retire_after_updates 50, --gate_probability 0.95, --max_gap_m 0.5.
//
// The mapper is slam::LaserSlam (slam/laser_slam.h), as ekf_slam_mapper runs it; the defaults are
// its defaults, the same on every log. --front_end 1 (default): each scan is first
// matched against the last keyframes (slam/scan_matcher.h), and the matched pose stands in for the
// wheel odometry in the EKF's prediction, with the front end's noise; its own trajectory goes to
// OUTPUT/laser_odometry.tum and its relation error to the summary
// (front_end_relation_trans_error_m, -1 without). --loop_closing 1 (default): a pose graph over
// keyframes of the EKF's trajectory with loop edges from scan matching (slam/pose_graph.h);
// OUTPUT/estimate.tum then holds every scan's optimised pose (OUTPUT/ekf.tum the EKF's own), and
// the relation keys are of the optimised trajectory (ekf_relation_trans_error_m: the EKF's).
// --wide_search 1 (default): loops the estimate has drifted metres from are searched for by branch
// and bound (LoopClosingConfig::wide_search; summary keys wide_attempts, wide_matches,
// wide_confirmed, wide_ambiguous: matches dropped as ambiguous in rotation, wide_budget_cut:
// searches the time bound cut short, wide_beyond_window: matches beyond the window of the node
// they join).
// `--front_end 0 --loop_closing 0` is the paper's filter alone, on the wheel odometry with
// --odom_noise_scale times its noise model (the simulator's consistency checks run it so).
// No returns: as ekf_slam_mapper does, a value repeated at the largest readings below the scans'
// range_max is found and those readings taken for no return (laser/no_return.h; summary key
// no_returns_marked); --keep_stated_range_max takes range_max as stated.
// Odometry: nav_msgs/Odometry on `odom`, the message nearest each scan; base_link -> laser from
// /tf_static (identity when absent). The external variant simulates an absolute position sensor
// from ground_truth/pose with --external_std_m noise on every scan (the bag must have ground
// truth). Summary keys (last line):
//   evaluate_slam: variant=.. ate_m=.. final_position_error_m=.. odometry_final_position_error_m=..
//       nees_in_bounds=.. nees_below_bounds=.. nees_mean=.. nis_per_dof=..
//       relation_trans_error_m=.. relation_trans_error_m_std=.. relation_rot_error_deg=..
//       relation_rot_error_deg_std=.. landmarks=.. fixed_landmarks=.. merged=.. (landmark pairs
//       merged as the same wall over the run) scans=.. update_ms_mean=.. update_ms_max=..
//       realtime_factor=..
// ate_m: RMS position error over the scans (no alignment: the map frame starts at the first true
// pose; with --loop_closing, of the optimised trajectory). nees_in_bounds: share of scans whose
// pose NEES lies inside the 95% chi-square interval of 3 degrees of freedom; nees_below_bounds the
// share below it (under-confident: the rest of the misses are over-confident); nees_mean should be
// near 3. nis_per_dof: the normalised innovation squared of the line updates summed over the run
// over their degrees of freedom (near 1 for a consistent filter; needs no ground truth, so it also
// checks real logs). For the anchor variant the truth is first expressed in the frame the anchored
// line and the fixed intersection define (matched to the true walls of ground_truth/walls).
// Relation keys: the Kuemmerle et al. metric against --relations (Freiburg format, bag stamps). -1
// where not available. --make_relations writes reference relations from ground_truth/pose (1 s
// chain + 200 random pairs). Writes OUTPUT/estimate.tum, truth.tum, odometry.tum,
// pose_covariance.csv, nees.csv (per scan with ground truth: NEES and the pose error), nis.csv (per
// scan: NIS, dof, landmarks merged), landmarks.csv, map.png (the line landmarks), line_map.yaml
// (the EKF's map as ~save_map writes it, for ekf_slam_mapper's ~initial_map) and the occupancy grid
// of every scan at its final pose (estimate.tum's) in map_server's files, map.yaml + map.pgm
// (slam/occupancy_grid.h, 0.05 m), and map_grid.png.
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <opencv2/imgcodecs.hpp>

#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/laser/line_extraction.h"
#include "adaptive_perception/laser/no_return.h"
#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/chi_square.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/slam/laser_slam.h"
#include "adaptive_perception/slam/line_ekf_slam.h"
#include "adaptive_perception/slam/map_drawing.h"
#include "adaptive_perception/slam/map_io.h"
#include "adaptive_perception/slam/occupancy_grid.h"
#include "adaptive_perception/slam/relations.h"
#include "adaptive_perception/world/camera_model.h"
#include "command_line.h"
#include "progress.h"

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

bool isTopic(const rosbag::MessageInstance& m, const std::string& name) {
  return m.getTopic() == name || m.getTopic() == "/" + name;
}

/// The true wall lines in map (from ground_truth/walls pieces in the laser frame and the true
/// pose).
std::vector<slam::Line> trueLines(
    const std::vector<std::pair<ros::Time, std::vector<laser::TrueWallPiece>>>& walls,
    const std::map<ros::Time, math::SE2>& truth, const math::SE2& mount) {
  std::vector<slam::Line> out;
  for (const auto& [stamp, pieces] : walls) {
    const math::SE2* g = nearest(truth, stamp);
    if (!g) continue;
    const math::SE2 sensor = *g * mount;
    for (const auto& piece : pieces) {
      const slam::Line l =
          slam::lineToMap(sensor, slam::lineThrough(piece.start_m, piece.end_m), nullptr, nullptr);
      bool seen = false;
      for (const auto& o : out)
        seen |= std::fabs(o.rho_m - l.rho_m) < 0.05 &&
                std::fabs(math::angleDiff(o.alpha_rad, l.alpha_rad)) < 0.02;
      if (!seen) out.push_back(l);
    }
  }
  return out;
}

/// Ground truth -> the frame the anchor variant defines (identity before both references are set).
math::SE2 anchorFrame(const slam::LineEkfSlam& ekf, const std::vector<slam::Line>& truth_lines) {
  // The references: the anchored line, then the gauge line (its intersection with the first).
  std::vector<slam::Line> refs;
  for (int k = 0; k < ekf.numFixedLandmarks(); ++k)
    if (ekf.fixedLandmark(k).anchor) refs.push_back(ekf.fixedLandmark(k).line);
  for (int i = 0; i < ekf.numLandmarks(); ++i)
    if (ekf.landmarkInfo(i).gauge) refs.push_back(ekf.landmark(i));
  std::vector<slam::Line> est, tru;
  for (size_t k = 0; k < refs.size() && est.size() < 2; ++k) {
    const slam::Line& line = refs[k];
    double best = 1e300;
    slam::Line match;
    for (const auto& t : truth_lines) {
      const double d = std::fabs(t.rho_m - line.rho_m) +
                       2.0 * std::fabs(math::angleDiff(t.alpha_rad, line.alpha_rad));
      if (d < best) {
        best = d;
        match = t;
      }
    }
    if (best > 1.0) continue;
    est.push_back(line);
    tru.push_back(match);
  }
  if (est.size() < 2) return math::SE2();
  // Rotation from the first reference (two undirected lines: the turn nearer zero), translation
  // carrying the true intersection of the references onto the estimated one: exactly the frame
  // the anchored line and the fixed intersection define (the gauge line's own direction is
  // still an estimate, so its rho is not used).
  double th = math::wrapAngle(est[0].alpha_rad - tru[0].alpha_rad);
  if (std::cos(th) < 0.0) th = math::wrapAngle(th + math::kPi);
  auto intersection = [](const slam::Line& a, const slam::Line& b) {
    Eigen::Matrix2d n;
    n << std::cos(a.alpha_rad), std::sin(a.alpha_rad), std::cos(b.alpha_rad), std::sin(b.alpha_rad);
    return Eigen::Vector2d(n.inverse() * Eigen::Vector2d(a.rho_m, b.rho_m));
  };
  const Eigen::Vector2d pe = intersection(est[0], est[1]), pt = intersection(tru[0], tru[1]);
  const Eigen::Vector2d t = pe - Eigen::Rotation2Dd(th) * pt;
  return math::SE2(t.x(), t.y(), th);
}
}  // namespace

int main(int argc, char** argv) {
  tools::CommandLine cli("evaluate_slam",
                         "Line extraction and line-landmark EKF SLAM offline over a laser bag "
                         "(simulator or a converted CARMEN log), against ground_truth/pose when "
                         "the bag has it, or the benchmark's relations.");
  const std::string& bag_path = cli.inputBag("laser bag (carmen_to_bag, simulate_laser)");
  slam::LaserSlamConfig slam_cfg;
  slam::LineEkfSlamConfig& cfg = slam_cfg.ekf;
  cli.word("association", &cfg.association.method, slam::associations(), "data association");
  cli.word("variant", &cfg.variant, slam::variants(), "filter variant");
  std::string relations_path;
  cli.option("relations", &relations_path, "relations file scored against (the benchmark's)");
  std::string make_relations;
  cli.option("make_relations", &make_relations,
             "writes relations from the bag's ground truth to this file");
  double external_std = 0.1;
  cli.option("external_std_m", &external_std, config::aboveZero(1e3),
             "variant external: standard deviation of the external position fixes, m");
  const std::uint64_t& seed = cli.seed();
  long long max_scans = 0;
  cli.option("max_scans", &max_scans, config::closed(0, 1e12), "scans processed (0: all)");
  const std::string& output = cli.resultsFolder("the results and plots");
  std::string name;
  cli.option("name", &name, "title of the run (empty: the bag's file name)");
  double odom_scale = 1.0;
  cli.option("odom_noise_scale", &odom_scale, config::aboveZero(1e3),
             "scales every odometry noise parameter of the motion models");
  // ekf_slam_mapper's and line_extractor's parameters (the same names and ranges), e.g.
  // --retire_after_updates 50, --loop_closing 0.
  cli.fields(slam::LaserSlamConfig::fields(), &slam_cfg);
  bool keep_stated_range_max = false;
  cli.flag("keep_stated_range_max", &keep_stated_range_max,
           "take the scans' range_max as stated (by default, as ekf_slam_mapper does, a value "
           "repeated at the largest readings below it is found and taken for no return)");
  laser::LineExtractionConfig lines;
  cli.fields(laser::LineExtractionConfig::fields(), &lines);
  cli.parse(argc, argv);
  if (name.empty()) name = fs::path(bag_path).stem().string();
  math::Rng rng(seed);
  const std::string variant = slam::variantName(cfg.variant);
  const bool loop_closing = slam_cfg.loop_closing;
  for (localization::MotionModelConfig* m : {&cfg.motion, &slam_cfg.front_end_motion})
    for (double* a : {&m->alpha1, &m->alpha2, &m->alpha3, &m->alpha4, &m->min_translation_std_m,
                      &m->min_rotation_std_rad})
      *a *= odom_scale;
  try {
    slam_cfg.validate();
    if (external_std <= 0.0) throw std::invalid_argument("--external_std_m must be > 0");
    const std::vector<slam::Relation> relations = relations_path.empty()
                                                      ? std::vector<slam::Relation>()
                                                      : slam::readRelations(relations_path);
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    std::vector<sensor_msgs::LaserScanConstPtr> scans;
    std::map<ros::Time, math::SE2> odom, truth;
    std::vector<std::pair<ros::Time, std::vector<laser::TrueWallPiece>>> walls;
    math::SE2 mount;
    for (const auto& m : rosbag::View(bag)) {
      if (auto s = m.instantiate<sensor_msgs::LaserScan>()) {
        scans.push_back(s);
      } else if (auto o = m.instantiate<nav_msgs::Odometry>()) {
        odom[o->header.stamp] = ros_conv::toSE2(o->pose.pose);
      } else if (auto g = m.instantiate<geometry_msgs::PoseStamped>()) {
        if (isTopic(m, ros_topics::kGroundTruthPose))
          truth[g->header.stamp] = ros_conv::toSE2(g->pose);
      } else if (auto w = m.instantiate<adaptive_perception::LineSegmentArray>()) {
        if (cfg.variant == slam::Variant::kAnchor && isTopic(m, "ground_truth/walls"))
          walls.emplace_back(w->header.stamp, ros_conv::wallPieces(*w));
      } else if (auto tf = m.instantiate<tf2_msgs::TFMessage>()) {
        if (m.getTopic() == "/tf_static")
          for (const auto& t : tf->transforms)
            if (t.child_frame_id == ros_topics::kLaserFrame)
              mount = world::isometryToPlanar(ros_conv::toIsometry(t.transform));
      }
    }
    if (scans.empty()) throw std::runtime_error(bag_path + ": no sensor_msgs/LaserScan messages");
    if (odom.empty()) throw std::runtime_error(bag_path + ": no nav_msgs/Odometry on odom");
    if (max_scans > 0 && static_cast<long long>(scans.size()) > max_scans) scans.resize(max_scans);
    if (cfg.variant == slam::Variant::kExternal && truth.empty())
      throw std::runtime_error(
          bag_path +
          ": the external variant simulates its sensor from ground_truth/pose, "
          "which this bag lacks");
    if (!make_relations.empty()) {
      if (truth.empty())
        throw std::runtime_error(bag_path + ": --make_relations needs ground_truth/pose");
      std::map<double, math::SE2> t;
      for (const auto& [stamp, p] : truth) t[stamp.toSec()] = p;
      slam::writeRelations(make_relations, slam::relationsFromTrajectory(t, 1.0, 200));
    }
    const math::SE2* t0 = nearest(truth, scans.front()->header.stamp);
    slam::LaserSlam slam(slam_cfg, t0 ? *t0 : math::SE2());
    const slam::LineEkfSlam& ekf = slam.ekf();
    laser::LineExtractor extractor(lines);
    fs::create_directories(output);
    std::ofstream ekf_tum(fs::path(output) / "ekf.tum"), truth_tum(fs::path(output) / "truth.tum"),
        odom_tum(fs::path(output) / "odometry.tum");
    std::ofstream cov_csv(fs::path(output) / "pose_covariance.csv");
    cov_csv << "t,xx,xy,yy,yawyaw\n";
    const double nees_lo = math::chiSquareQuantile(0.025, 3),
                 nees_hi = math::chiSquareQuantile(0.975, 3);
    double sq = 0.0, final_err = -1.0, compute_s = 0.0, odom_final_err = -1.0, max_update_s = 0.0;
    math::SE2 dead_reckoning = ekf.pose();  // odometry alone, from the same start
    long with_truth = 0;
    double nis_sum = 0.0;
    long nis_dof = 0, nis_rows = 0;
    std::ofstream nis_csv(fs::path(output) / "nis.csv");
    nis_csv << "scan,nis,dof,merged\n";
    long merged = 0;
    const math::SE2* prev_odom = nullptr;
    std::map<double, math::SE2> estimate, front_estimate;
    std::vector<double> scan_stamps;
    std::vector<std::pair<double, laser::LaserScan2D>> kept_scans;  // for the occupancy grid
    laser::NoReturnFinder no_return;  // as ekf_slam_mapper's (laser/no_return.h)
    long no_returns_marked = 0;
    std::ofstream front_tum;
    if (slam_cfg.front_end) front_tum.open(fs::path(output) / "laser_odometry.tum");
    std::vector<std::pair<math::SE2, Eigen::Matrix3d>> est_cov;
    std::vector<math::SE2> truth_at_scan;
    slam::MapTrajectory est_path{"estimate", cv::Scalar(0, 0, 220), {}},
        truth_path{"ground truth", cv::Scalar(0, 160, 0), {}},
        odom_path{"odometry", cv::Scalar(160, 160, 160), {}};
    tools::Progress progress("evaluate_slam", static_cast<long>(scans.size()), "scans");
    for (const auto& s : scans) {
      progress.update(static_cast<long>(&s - scans.data()) + 1);
      const math::SE2* o = nearest(odom, s->header.stamp);
      const math::SE2* g = nearest(truth, s->header.stamp);
      if (prev_odom) dead_reckoning = dead_reckoning * math::between(*prev_odom, *o);
      prev_odom = o;
      const auto c0 = std::chrono::steady_clock::now();
      laser::LaserScan2D scan2d = ros_conv::fromLaserScan(*s);
      if (!keep_stated_range_max) {
        bool found_now = false;
        no_returns_marked += no_return.mark(&scan2d.ranges_m, scan2d.range_max_m, &found_now);
        if (found_now)
          std::fprintf(stderr,
                       "evaluate_slam: the scans' range_max is %.2f m, but %ld readings are "
                       "exactly %.2f m: taken for the laser's no-return value (not walls)\n",
                       scan2d.range_max_m, no_return.readingsAtValue(), *no_return.value());
      }
      std::vector<Eigen::Vector2d> robot;
      if (slam_cfg.front_end || loop_closing) {
        std::vector<laser::ScanPoint> pts;
        laser::validPoints(scan2d, 0.0, &pts);
        robot.reserve(pts.size());
        for (const auto& p : pts) robot.push_back(mount.transformPoint(p.p_m));
      }
      slam::LaserSlam::ExternalPosition external;
      const bool with_external = cfg.variant == slam::Variant::kExternal && g;
      if (with_external) {
        external.xy_m = Eigen::Vector2d(g->x_m + rng.gaussian(0.0, external_std),
                                        g->y_m + rng.gaussian(0.0, external_std));
        external.cov = Eigen::Matrix2d::Identity() * external_std * external_std;
      }
      const slam::LaserSlam::Step step =
          slam.add(robot, slam::toObservations(extractor.extract(scan2d), mount), *o,
                   with_external ? &external : nullptr);
      const slam::LineEkfSlam::UpdateResult& up = step.ekf;
      if (slam_cfg.front_end) {
        front_estimate[s->header.stamp.toSec()] = step.prediction;
        tum(front_tum, s->header.stamp.toSec(), step.prediction);
      }
      nis_sum += up.nis;
      nis_dof += up.nis_dof;
      nis_csv << nis_rows++ << "," << up.nis << "," << up.nis_dof << "," << up.merged << "\n";
      merged += up.merged;
      const double dt =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
      compute_s += dt;
      max_update_s = std::max(max_update_s, dt);
      const double t = s->header.stamp.toSec();
      estimate[t] = ekf.pose();
      kept_scans.emplace_back(t, scan2d);
      tum(ekf_tum, t, ekf.pose());
      scan_stamps.push_back(t);
      const Eigen::Matrix3d pc = ekf.poseCovariance();
      cov_csv << std::fixed << t << "," << pc(0, 0) << "," << pc(0, 1) << "," << pc(1, 1) << ","
              << pc(2, 2) << "\n";
      tum(odom_tum, t, dead_reckoning);
      est_path.points_m.emplace_back(ekf.pose().x_m, ekf.pose().y_m);
      odom_path.points_m.emplace_back(dead_reckoning.x_m, dead_reckoning.y_m);
      if (g) {
        tum(truth_tum, t, *g);
        truth_path.points_m.emplace_back(g->x_m, g->y_m);
        sq += std::pow(ekf.pose().x_m - g->x_m, 2) + std::pow(ekf.pose().y_m - g->y_m, 2);
        final_err = std::hypot(ekf.pose().x_m - g->x_m, ekf.pose().y_m - g->y_m);
        odom_final_err = std::hypot(dead_reckoning.x_m - g->x_m, dead_reckoning.y_m - g->y_m);
        est_cov.emplace_back(ekf.pose(), ekf.poseCovariance());
        truth_at_scan.push_back(*g);
        ++with_truth;
      }
    }
    const std::map<double, math::SE2> ekf_estimate = estimate;
    if (loop_closing) {
      std::ofstream loops(fs::path(output) / "loop_edges.csv");
      loops << "t_from,t_to,dx_m,dy_m,dyaw_rad,score,wide\n";
      for (const auto& e : slam.loopCloser().loopEdges())
        loops << std::fixed << scan_stamps.at(e.scan_from) << "," << scan_stamps.at(e.scan_to)
              << "," << e.relative.x_m << "," << e.relative.y_m << "," << e.relative.yaw_rad << ","
              << e.score << "," << (e.wide ? 1 : 0) << "\n";
      const std::vector<math::SE2> final_poses = slam.trajectory();
      for (size_t i = 0; i < scan_stamps.size(); ++i) estimate[scan_stamps[i]] = final_poses[i];
      est_path.points_m.clear();
      for (const auto& [t, p] : estimate) est_path.points_m.emplace_back(p.x_m, p.y_m);
      // ate_m and final_position_error_m are of the optimised trajectory.
      if (with_truth > 0) {
        sq = 0.0;
        for (const auto& [t, p] : estimate) {
          const math::SE2* g = nearest(truth, ros::Time(t));
          if (!g) continue;
          final_err = std::hypot(p.x_m - g->x_m, p.y_m - g->y_m);
          sq += final_err * final_err;
        }
      }
    }
    {
      std::ofstream est_tum(fs::path(output) / "estimate.tum");
      for (const auto& [t, p] : estimate) tum(est_tum, t, p);
    }
    // The occupancy grid of every scan at its final pose: map_server's files and a picture.
    const auto c_grid = std::chrono::steady_clock::now();
    std::vector<laser::LaserScan2D> grid_scans;
    std::vector<math::SE2> grid_poses;
    grid_scans.reserve(kept_scans.size());
    for (auto& [t, scan] : kept_scans) {
      grid_poses.push_back(estimate.at(t) * mount);
      grid_scans.push_back(std::move(scan));
    }
    const slam::OccupancyGrid grid = slam::renderOccupancyGrid(grid_scans, grid_poses);
    slam::writeMapServerFiles(grid, (fs::path(output) / "map.yaml").string());
    cv::imwrite((fs::path(output) / "map_grid.png").string(), slam::drawOccupancyGrid(grid));
    const double grid_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - c_grid).count();
    // NEES, in the anchored frame for the anchor variant (known only once both anchors are fixed;
    // the frame is the same from the moment they are, and before that the map is the start frame).
    const math::SE2 frame = cfg.variant == slam::Variant::kAnchor
                                ? anchorFrame(ekf, trueLines(walls, truth, mount))
                                : math::SE2();
    long in_bounds = 0, below = 0;
    double nees_sum = 0.0;
    std::ofstream nees_csv(fs::path(output) / "nees.csv");
    nees_csv << "scan,nees,err_x_m,err_y_m,err_yaw_rad\n";
    for (size_t i = 0; i < est_cov.size(); ++i) {
      const math::SE2 g = frame * truth_at_scan[i];
      const math::SE2& e = est_cov[i].first;
      const Eigen::Vector3d err(e.x_m - g.x_m, e.y_m - g.y_m,
                                math::angleDiff(e.yaw_rad, g.yaw_rad));
      const double nees = err.dot(est_cov[i].second.ldlt().solve(err));
      in_bounds += nees >= nees_lo && nees <= nees_hi;
      below += nees < nees_lo;
      nees_sum += nees;
      nees_csv << i << "," << nees << "," << err.x() << "," << err.y() << "," << err.z() << "\n";
    }
    std::ofstream lm(fs::path(output) / "landmarks.csv");
    lm << "rho_m,alpha_rad,x0,y0,x1,y1,sightings,fixed\n";
    std::vector<slam::MapSegment> segments;
    auto write = [&](const slam::Line& l, const slam::Landmark& info, bool fixed) {
      lm << l.rho_m << "," << l.alpha_rad << "," << info.start_m.x() << "," << info.start_m.y()
         << "," << info.end_m.x() << "," << info.end_m.y() << "," << info.sightings << ","
         << (fixed ? 1 : 0) << "\n";
      if (info.confirmed())
        for (const auto& pc : info.pieces) segments.push_back({pc.first, pc.second, fixed});
    };
    for (int i = 0; i < ekf.numLandmarks(); ++i) write(ekf.landmark(i), ekf.landmarkInfo(i), false);
    for (int k = 0; k < ekf.numFixedLandmarks(); ++k)
      write(ekf.fixedLandmark(k).line, ekf.fixedLandmark(k).info, true);
    slam::writeLineMapYaml((fs::path(output) / "line_map.yaml").string(), ekf);
    std::vector<slam::MapTrajectory> paths{odom_path, est_path};
    if (!truth_path.points_m.empty()) paths.insert(paths.begin() + 1, truth_path);
    cv::imwrite((fs::path(output) / "map.png").string(),
                slam::drawLineMap(segments, paths, name + " (" + variant + ")"));
    slam::RelationErrors rel, front_rel, ekf_rel;
    if (!relations.empty()) {
      rel = slam::evaluateRelations(relations, estimate, 0.01);
      ekf_rel = slam::evaluateRelations(relations, ekf_estimate, 0.01);
      if (!front_estimate.empty())
        front_rel = slam::evaluateRelations(relations, front_estimate, 0.01);
      if (rel.used == 0)
        throw std::runtime_error(relations_path + ": no relation matches the bag's scan stamps");
    }
    int confirmed = 0;  // tentative landmarks are not part of the map
    for (int i = 0; i < ekf.numLandmarks(); ++i) confirmed += ekf.landmarkInfo(i).confirmed();
    const double duration = (scans.back()->header.stamp - scans.front()->header.stamp).toSec();
    const bool has_rel = !relations.empty();
    std::printf(
        "evaluate_slam: variant=%s ate_m=%.3f final_position_error_m=%.3f "
        "odometry_final_position_error_m=%.3f nees_in_bounds=%.3f nees_below_bounds=%.3f "
        "nees_mean=%.2f "
        "nis_per_dof=%.2f relation_trans_error_m=%.4f "
        "relation_trans_error_m_std=%.4f relation_rot_error_deg=%.3f "
        "relation_rot_error_deg_std=%.3f relations_used=%d landmarks=%d fixed_landmarks=%d "
        "merged=%ld scans=%zu update_ms_mean=%.3f update_ms_max=%.3f realtime_factor=%.1f "
        "front_end=%s front_end_relation_trans_error_m=%.4f front_end_relation_rot_error_deg=%.3f "
        "front_end_matched=%.3f front_end_weak_matches=%ld loop_closures=%d graph_nodes=%d "
        "ekf_relation_trans_error_m=%.4f chain_edges_replaced=%d loops_rejected_free_space=%ld "
        "wide_attempts=%ld wide_matches=%ld wide_confirmed=%ld wide_ambiguous=%ld "
        "wide_budget_cut=%ld wide_beyond_window=%ld wide_s=%.1f "
        "grid_cells=%dx%d "
        "grid_s=%.1f no_returns_marked=%ld\n",
        variant.c_str(), with_truth ? std::sqrt(sq / with_truth) : -1.0, final_err, odom_final_err,
        with_truth ? double(in_bounds) / with_truth : -1.0,
        with_truth ? double(below) / with_truth : -1.0, with_truth ? nees_sum / with_truth : -1.0,
        nis_dof ? nis_sum / nis_dof : -1.0, has_rel ? rel.trans_mean_m : -1.0,
        has_rel ? rel.trans_std_m : -1.0, has_rel ? math::radToDeg(rel.rot_mean_rad) : -1.0,
        has_rel ? math::radToDeg(rel.rot_std_rad) : -1.0, rel.used, confirmed,
        ekf.numFixedLandmarks(), merged, scans.size(), 1e3 * compute_s / scans.size(),
        1e3 * max_update_s, duration / std::max(compute_s, 1e-9),
        slam_cfg.front_end ? "laser_odometry" : "none",
        has_rel && !front_estimate.empty() ? front_rel.trans_mean_m : -1.0,
        has_rel && !front_estimate.empty() ? math::radToDeg(front_rel.rot_mean_rad) : -1.0,
        slam.frontEnd().scans() ? double(slam.frontEnd().matched()) / slam.frontEnd().scans()
                                : -1.0,
        slam.frontEnd().weakMatchesRejected(), slam.loopCloser().loopClosures(),
        slam.loopCloser().nodes(), has_rel ? ekf_rel.trans_mean_m : -1.0,
        slam.loopCloser().chainEdgesReplaced(), slam.loopCloser().freeSpaceRejections(),
        slam.loopCloser().wideAttempts(), slam.loopCloser().wideMatches(),
        slam.loopCloser().wideConfirmed(), slam.loopCloser().wideAmbiguous(),
        slam.loopCloser().wideBudgetCut(), slam.loopCloser().wideBeyondWindow(),
        slam.loopCloser().wideSeconds(), grid.width, grid.height, grid_s, no_returns_marked);
  } catch (const std::exception& e) {
    std::cerr << "evaluate_slam: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
