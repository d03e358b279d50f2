#include "adaptive_perception/ros/ekf_slam_mapper_node.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>

#include "adaptive_perception/io/atomic_file.h"
#include "adaptive_perception/math/chi_square.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/parameter_docs.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/slam/map_io.h"
#include "adaptive_perception/world/camera_model.h"
#include "adaptive_perception/ros/node_run.h"

namespace adaptive_perception {

namespace fs = std::filesystem;
using ros_params::ParamError;

namespace {
// The node's own parameters' defaults (the algorithm's are in slam::LaserSlamConfig, the variant's
// and the association's too).
constexpr char kDefaultMapFile[] = "line_map.yaml";
const std::vector<double> kMapperInitialPoseStd = {1e-3, 1e-3, 1e-3};
constexpr double kExternalGate = 0.999, kMapperTransformTolerance_s = 0.1, kMapperTfTimeout_s = 0.2;
constexpr double kMapUpdateInterval_s = 5.0;
constexpr double kGridKeyframeDistance_m = 0.1, kGridKeyframeAngle_rad = 0.1;
constexpr int kPathMaxPoses = 20000;
}  // namespace

std::vector<config::ParameterDoc> EkfSlamMapperNode::parameters() {
  namespace P = ros_params;
  const slam::OccupancyGridConfig grid;
  const slam::LineEkfSlamConfig ekf;
  return P::joinRows(
      {config::describe(slam::LaserSlamConfig::fields(), slam::LaserSlamConfig()),
       {P::wordParameter("variant", slam::variants(), ekf.variant,
                         "standard; anchor: two non-parallel lines fixed; external: absolute "
                         "poses on external_pose"),
        P::wordParameter("association", slam::associations(), ekf.association.method,
                         "jcbb: joint compatibility branch and bound; nn: nearest neighbour"),
        {"initial_map", "string", "", "",
         "a line map written by ~save_map: localize against it, never extend it (loop closing "
         "off); empty: map"},
        {"initial_pose", "list", "[]", "",
         "[x_m, y_m, yaw_rad] at the first scan; empty: the origin"},
        {"initial_pose_std", "list", config::formatList(kMapperInitialPoseStd), "",
         "its standard deviations (m, m, rad)"},
        {"external_gate_probability", "double", config::formatReal(kExternalGate),
         "[0.5, 0.999999]",
         "external poses whose innovation fails this chi-square gate are rejected"},
        ros_params::frameParameter("map"),
        ros_params::frameParameter("odom"),
        ros_params::frameParameter("base"),
        {"publish_tf", "bool", "true", "", "broadcast map -> odom"},
        {"transform_tolerance_s", "double", config::formatReal(kMapperTransformTolerance_s),
         "[0, 10]", "map -> odom is future-dated by this (s), as amcl does"},
        ros_conv::MeasurementTf::parameter(kMapperTfTimeout_s, "odom -> base_link -> laser"),
        {"map_file", "string", kDefaultMapFile, "",
         "~save_map's default path (relative to the node's working directory)"},
        {"path_max_poses", "int", std::to_string(kPathMaxPoses), "[1, 10000000]",
         "ekf_slam_mapper/path keeps the newest poses"},
        {"map_update_interval_s", "double", config::formatReal(kMapUpdateInterval_s), "[0, 3600]",
         "seconds between occupancy-grid renders (gmapping's map_update_interval); 0: no grid"},
        {"grid_resolution_m", "double", config::formatReal(grid.resolution_m), "[0.005, 10]",
         "the grid's cell side (m)"},
        {"grid_max_range_m", "double", config::formatReal(grid.max_range_m), "[0.1, 1000]",
         "beams are used up to here; no-returns clear up to here (m)"},
        {"grid_keyframe_distance_m", "double", config::formatReal(kGridKeyframeDistance_m),
         "[0, 100]", "the grid keeps a scan after this much motion (m)"},
        {"grid_keyframe_angle_rad", "double", config::formatReal(kGridKeyframeAngle_rad),
         "[0, 3.14159]", "... or this much turning (rad)"},
        ros_params::stampOrderParameter()}});
}

EkfSlamMapperNode::EkfSlamMapperNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : tf_("ekf_slam_mapper", pnh, kMapperTfTimeout_s),
      diagnostics_(nh, "ekf_slam_mapper", 1.0, 100.0, &mutex_) {
  namespace P = ros_params;
  P::loadFields(pnh, slam::LaserSlamConfig::fields(), &config_);
  slam::LineEkfSlamConfig& c = config_.ekf;
  c.variant = P::getWord(pnh, "variant", slam::variants(), c.variant);
  c.association.method = P::getWord(pnh, "association", slam::associations(), c.association.method);
  P::loadInitialPose(pnh, kMapperInitialPoseStd, &initial_pose_, &initial_cov_);
  initial_map_ = P::get<std::string>(pnh, "initial_map", "");
  if (!initial_map_.empty()) {
    try {
      known_map_ = slam::readLineMapYaml(initial_map_);
    } catch (const std::exception& e) {
      throw ParamError(std::string("~initial_map: ") + e.what());
    }
    c.extend_map = false;  // localize against the loaded map, never extend it
    config_.loop_closing = false;
  }
  external_gate_ = P::getInRange(pnh, "external_gate_probability", kExternalGate, 0.5, 0.999999);
  map_frame_ = P::getFrameId(pnh, "map_frame", ros_topics::kMapFrame);
  odom_frame_ = P::getFrameId(pnh, "odom_frame", ros_topics::kOdomFrame);
  base_frame_ = P::getFrameId(pnh, "base_frame", ros_topics::kBaseFrame);
  publish_tf_ = P::get<bool>(pnh, "publish_tf", true);
  transform_tolerance_s_ =
      P::getInRange(pnh, "transform_tolerance_s", kMapperTransformTolerance_s, 0.0, 10.0);
  stamp_order_ = ros_conv::StampOrder("ekf_slam_mapper", "lines", P::loadStampOrder(pnh));
  map_file_ = P::get<std::string>(pnh, "map_file", kDefaultMapFile);
  path_max_poses_ = P::getInRange(pnh, "path_max_poses", kPathMaxPoses, 1, 10000000);
  grid_config_.resolution_m =
      P::getInRange(pnh, "grid_resolution_m", grid_config_.resolution_m, 0.005, 10.0);
  grid_config_.max_range_m =
      P::getInRange(pnh, "grid_max_range_m", grid_config_.max_range_m, 0.1, 1000.0);
  map_update_interval_s_ =
      P::getInRange(pnh, "map_update_interval_s", kMapUpdateInterval_s, 0.0, 3600.0);
  keyframes_ = std::make_unique<slam::GridKeyframes>(
      P::getInRange(pnh, "grid_keyframe_distance_m", kGridKeyframeDistance_m, 0.0, 100.0),
      P::getInRange(pnh, "grid_keyframe_angle_rad", kGridKeyframeAngle_rad, 0.0, M_PI));
  try {
    config_.validate();
    grid_config_.validate();
  } catch (const std::invalid_argument& e) {
    throw ParamError(std::string("ekf_slam_mapper parameters: ") + e.what());
  }
  slam_ = std::make_unique<slam::LaserSlam>(config_, initial_pose_, initial_cov_);
  slam_->ekf().addFixedLandmarks(known_map_);
  if (!initial_map_.empty())
    ROS_INFO("ekf_slam_mapper: localizing against %zu landmarks of %s (the map is not extended)",
             known_map_.size(), initial_map_.c_str());
  path_.header.frame_id = map_frame_;

  pose_pub_ = nh.advertise<geometry_msgs::PoseWithCovarianceStamped>("ekf_slam_mapper/pose", 5);
  map_pub_ = nh.advertise<visualization_msgs::MarkerArray>("ekf_slam_mapper/map", 1, true);
  path_pub_ = nh.advertise<nav_msgs::Path>("ekf_slam_mapper/path", 1, true);
  // Queues long enough to ride out a slow update (a loop closure's optimisation: at most 0.7 s on
  // fr-clinic), short enough to bound the delay when the input comes faster than the mapper can
  // take it: 30 messages are 3 s of a 10 Hz laser. With 100, a 10x storm of scans
  // (hostile_ekf_slam_mapper) queued 2.2 s of work beside other tests, and the mapper answered
  // the next pass with stale poses.
  constexpr uint32_t kInputQueue = 30;
  lines_sub_ = nh.subscribe("lines", kInputQueue, &EkfSlamMapperNode::onLines, this);
  if (config_.ekf.variant == slam::Variant::kExternal)
    external_sub_ = nh.subscribe("external_pose", 20, &EkfSlamMapperNode::onExternalPose, this);
  save_srv_ =
      service_queue_.handle(pnh).advertiseService("save_map", &EkfSlamMapperNode::onSaveMap, this);
  reset_srv_ =
      service_queue_.handle(pnh).advertiseService("reset", &EkfSlamMapperNode::onReset, this);
  if (map_update_interval_s_ > 0.0 || config_.front_end || config_.loop_closing)
    scan_sub_ = nh.subscribe(ros_topics::kScan, kInputQueue, &EkfSlamMapperNode::onScan, this);
  if (map_update_interval_s_ > 0.0) {
    grid_pub_ = nh.advertise<nav_msgs::OccupancyGrid>("map", 1, true);
    grid_meta_pub_ = nh.advertise<nav_msgs::MapMetaData>("map_metadata", 1, true);
    get_map_srv_ = service_queue_.handle(nh).advertiseService("dynamic_map",
                                                              &EkfSlamMapperNode::onGetMap, this);
    map_timer_ = service_queue_.handle(nh).createSteadyTimer(
        ros::WallDuration(map_update_interval_s_),
        [this](const ros::SteadyTimerEvent&) { onMapTimer(); });
  }
  diagnostics_.add("slam", this, &EkfSlamMapperNode::diagnose);
  ROS_INFO(
      "ekf_slam_mapper: variant %s, association %s, retirement %s, front end %s, loop "
      "closing %s",
      slam::variantName(config_.ekf.variant).c_str(),
      slam::associationName(config_.ekf.association.method).c_str(),
      config_.ekf.retire_after_updates > 0
          ? ("after " + std::to_string(config_.ekf.retire_after_updates) + " updates").c_str()
          : "off",
      config_.front_end ? "laser odometry" : "off (wheel odometry)",
      config_.loop_closing ? "on" : "off");
}

void EkfSlamMapperNode::reset(const char* why) {
  ROS_WARN("ekf_slam_mapper: %s: the map starts again", why);
  slam_ = std::make_unique<slam::LaserSlam>(config_, initial_pose_, initial_cov_);
  slam_->ekf().addFixedLandmarks(known_map_);
  path_.poses.clear();
  keyframes_->clear();
  grid_scan_index_.clear();
  grid_mount_.clear();
  recent_scans_.clear();
  waiting_lines_.clear();
  ++resets_;
}

void EkfSlamMapperNode::onLines(const ros::MessageEvent<const LineSegmentArray>& event) {
  std::vector<ros::MessageEvent<const LineSegmentArray>> ready;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const ros::Time stamp = event.getConstMessage()->header.stamp;
    const bool scan_due = scan_sub_ && scan_sub_.getNumPublishers() > 0 &&
                          (recent_scans_.empty() || recent_scans_.back()->header.stamp < stamp);
    if (scan_due || !waiting_lines_.empty()) waiting_lines_.push_back(event);
    if (!scan_due) {
      ready.assign(waiting_lines_.begin(), waiting_lines_.end());
      waiting_lines_.clear();
    } else if (waiting_lines_.size() > kMaxWaitingLines) {
      ready.push_back(waiting_lines_.front());  // its scan is not coming
      waiting_lines_.pop_front();
    }
    if (ready.empty() && !scan_due) ready.push_back(event);
  }
  for (const auto& e : ready) processLines(e);
}

void EkfSlamMapperNode::processLines(const ros::MessageEvent<const LineSegmentArray>& event) {
  const boost::shared_ptr<const LineSegmentArray> msg = event.getConstMessage();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // Lines a little older than the last are dropped; time really going back restarts below.
    if (stamp_order_.check(msg->header.stamp, event.getPublisherName()) ==
        ros_conv::StampOrder::Verdict::kDrop)
      return;
  }
  const std::optional<ros_conv::OdomAndMount> tf =
      tf_.odomAndMount(odom_frame_, base_frame_, msg->header.frame_id, msg->header.stamp, "scan");
  if (!tf) return;
  std::vector<laser::LineSegment> segments;
  long bad = 0;
  for (const auto& seg : ros_conv::fromLineSegmentArray(*msg)) {
    const bool finite = std::isfinite(seg.line.rho_m) && std::isfinite(seg.line.alpha_rad) &&
                        seg.line.cov.allFinite() && seg.start_m.allFinite() &&
                        seg.end_m.allFinite();
    if (finite && seg.line.cov(0, 0) >= 0.0 && seg.line.cov(1, 1) >= 0.0)
      segments.push_back(seg);
    else
      ++bad;
  }
  if (bad > 0)
    ROS_ERROR_THROTTLE(10.0,
                       "ekf_slam_mapper: %ld segment(s) with non-finite or negative values "
                       "dropped",
                       bad);
  std::lock_guard<std::mutex> lock(mutex_);
  bad_segments_ += bad;
  if (!last_stamp_.isZero() && msg->header.stamp < last_stamp_)
    reset("time went backwards (bag looped?)");
  last_stamp_ = msg->header.stamp;
  const Eigen::Isometry3d& odom = tf->odom_to_base;
  const math::SE2 mount = world::isometryToPlanar(tf->base_to_sensor);
  const auto t0 = std::chrono::steady_clock::now();
  // The scan these lines came from: its points for the front end and the loop closer, and the
  // grid's scan. Without it the front end follows the wheel odometry for this scan.
  sensor_msgs::LaserScanConstPtr scan;
  while (!recent_scans_.empty() && recent_scans_.front()->header.stamp < msg->header.stamp)
    recent_scans_.pop_front();
  if (!recent_scans_.empty() && recent_scans_.front()->header.stamp == msg->header.stamp) {
    scan = recent_scans_.front();
    recent_scans_.pop_front();
  } else if (scan_sub_) {
    ++scans_without_laser_scan_;
  }
  laser::LaserScan2D scan2d;
  std::vector<Eigen::Vector2d> points_robot;
  if (scan) scan2d = ros_conv::fromLaserScan(*scan);
  if (const std::string problem = scan ? laser::scanGeometryProblem(scan2d) : "";
      !problem.empty()) {
    ROS_ERROR_THROTTLE(10.0, "ekf_slam_mapper: scan's points not used: %s", problem.c_str());
    scan.reset();
    scan2d = laser::LaserScan2D();
  }
  if (scan) {
    bool found_now = false;
    no_returns_marked_ += no_return_.mark(&scan2d.ranges_m, scan2d.range_max_m, &found_now);
    if (found_now)
      ROS_WARN("ekf_slam_mapper: the scans' range_max is %.2f m, but %ld readings are exactly "
               "%.2f m and none spread below: taken for the laser's no-return value (not walls)",
               scan2d.range_max_m, no_return_.readingsAtValue(), *no_return_.value());
    std::vector<laser::ScanPoint> pts;
    laser::validPoints(scan2d, 0.0, &pts);
    points_robot.reserve(pts.size());
    for (const auto& p : pts) points_robot.push_back(mount.transformPoint(p.p_m));
  }
  try {
    slam_->add(points_robot, slam::toObservations(segments, mount), world::isometryToPlanar(odom));
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(10.0, "ekf_slam_mapper: update failed (%s): scan skipped", e.what());
    ++update_failures_;
    return;
  }
  // The grid keeps the scan, at the pose the mapper now gives it (moved when loops close).
  if (scan && map_update_interval_s_ > 0.0 && keyframes_->add(scan2d, slam_->pose() * mount)) {
    grid_scan_index_.push_back(slam_->scans() - 1);
    grid_mount_.push_back(mount);
  }
  last_update_ms_ =
      1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  max_update_ms_ = std::max(max_update_ms_, last_update_ms_);
  ++scans_;
  diagnostics_.tick();
  publish(msg->header, odom);
  diagnostics_.update();
}

void EkfSlamMapperNode::onScan(const sensor_msgs::LaserScanConstPtr& msg) {
  std::vector<ros::MessageEvent<const LineSegmentArray>> ready;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    recent_scans_.push_back(msg);
    while (recent_scans_.size() > 200) recent_scans_.pop_front();  // lines that never came
    while (!waiting_lines_.empty() &&
           waiting_lines_.front().getConstMessage()->header.stamp <= msg->header.stamp) {
      ready.push_back(waiting_lines_.front());
      waiting_lines_.pop_front();
    }
  }
  for (const auto& e : ready) processLines(e);
}

bool EkfSlamMapperNode::renderGrid(nav_msgs::OccupancyGrid* out, slam::OccupancyGrid* grid_out) {
  std::vector<laser::LaserScan2D> scans;
  std::vector<math::SE2> poses;
  ros::Time stamp;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    scans = keyframes_->scans();
    poses = keyframes_->poses();
    stamp = last_stamp_;
    if (config_.loop_closing) {
      const std::vector<math::SE2> trajectory = slam_->trajectory();
      for (size_t i = 0; i < poses.size(); ++i)
        poses[i] = trajectory.at(grid_scan_index_[i]) * grid_mount_[i];
    }
  }
  if (scans.empty()) return false;
  const auto t0 = std::chrono::steady_clock::now();
  const slam::OccupancyGrid grid = slam::renderOccupancyGrid(scans, poses, grid_config_);
  out->header.frame_id = map_frame_;
  out->header.stamp = stamp;
  out->info.map_load_time = stamp;
  out->info.resolution = static_cast<float>(grid.resolution_m);
  out->info.width = static_cast<std::uint32_t>(grid.width);
  out->info.height = static_cast<std::uint32_t>(grid.height);
  out->info.origin.position.x = grid.origin_x_m;
  out->info.origin.position.y = grid.origin_y_m;
  out->info.origin.orientation.w = 1.0;
  out->data.assign(grid.data.begin(), grid.data.end());
  std::lock_guard<std::mutex> lock(mutex_);
  last_grid_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++grid_renders_;
  if (grid_out) *grid_out = grid;
  return true;
}

void EkfSlamMapperNode::onMapTimer() {
  nav_msgs::OccupancyGrid grid;
  try {
    if (!renderGrid(&grid)) return;
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(30.0, "ekf_slam_mapper: occupancy grid not rendered: %s", e.what());
    return;
  }
  grid_meta_pub_.publish(grid.info);
  grid_pub_.publish(grid);
}

bool EkfSlamMapperNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  std::lock_guard<std::mutex> lock(mutex_);
  const int landmarks = slam_->ekf().numLandmarks() + slam_->ekf().numFixedLandmarks();
  const size_t keyframes = keyframes_->size();
  reset("reset requested");
  last_stamp_ = ros::Time();
  res.success = true;
  res.message = "forgot " + std::to_string(landmarks) + " landmarks and " +
                std::to_string(keyframes) + " grid scans; mapping again from ~initial_pose";
  return true;
}

bool EkfSlamMapperNode::onGetMap(nav_msgs::GetMap::Request&, nav_msgs::GetMap::Response& res) {
  try {
    return renderGrid(&res.map);  // false (the call fails) before the first scan
  } catch (const std::exception& e) {
    ROS_ERROR("ekf_slam_mapper: dynamic_map: %s", e.what());
    return false;
  }
}

void EkfSlamMapperNode::onExternalPose(
    const geometry_msgs::PoseWithCovarianceStampedConstPtr& msg) {
  if (!msg->header.frame_id.empty() && msg->header.frame_id != map_frame_) {
    ROS_ERROR_THROTTLE(10.0, "ekf_slam_mapper: external_pose in frame '%s' (expected '%s') ignored",
                       msg->header.frame_id.c_str(), map_frame_.c_str());
    std::lock_guard<std::mutex> lock(mutex_);
    ++external_rejected_;
    return;
  }
  ros_conv::PlanarPoseInput in;
  try {
    in = ros_conv::planarPoseInput(msg->pose, ros_conv::PoseYaw::kIfKnown);
  } catch (const std::invalid_argument& e) {
    ROS_ERROR_THROTTLE(10.0, "ekf_slam_mapper: external_pose ignored: %s", e.what());
    std::lock_guard<std::mutex> lock(mutex_);
    ++external_rejected_;
    return;
  }
  const math::SE2& z = in.pose;
  const Eigen::Matrix3d& cov = in.cov;
  const bool with_yaw = in.has_yaw;
  std::lock_guard<std::mutex> lock(mutex_);
  // Gate: a copy takes the update; the real filter follows only when the innovation is plausible.
  // A NaN innovation (d2) fails the gate too: the filter never takes a state it cannot undo.
  slam::LineEkfSlam trial = slam_->ekf();
  double d2 = std::numeric_limits<double>::quiet_NaN();
  try {
    d2 = with_yaw ? trial.updateExternalPose(z, cov)
                  : trial.updateExternalPosition(Eigen::Vector2d(z.x_m, z.y_m),
                                                 cov.topLeftCorner<2, 2>());
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(10.0, "ekf_slam_mapper: external_pose update failed: %s", e.what());
  }
  if (!(d2 <= math::chiSquareQuantile(external_gate_, with_yaw ? 3 : 2))) {
    ROS_WARN_THROTTLE(5.0, "ekf_slam_mapper: external pose rejected (Mahalanobis^2 %.1f)", d2);
    ++external_rejected_;
    return;
  }
  slam_->ekf() = std::move(trial);
  ++external_used_;
}

void EkfSlamMapperNode::publish(const std_msgs::Header& scan_header,
                                const Eigen::Isometry3d& odom_to_base) {
  std_msgs::Header h = scan_header;
  h.frame_id = map_frame_;
  const geometry_msgs::PoseWithCovarianceStamped pose =
      ros_conv::toPoseWithCovariance(slam_->pose(), slam_->ekf().poseCovariance(), h);
  pose_pub_.publish(pose);
  if (publish_tf_)
    tf_broadcaster_.sendTransform(ros_conv::toTransform(
        ros_conv::mapToOdom(slam_->pose(), odom_to_base), map_frame_, odom_frame_,
        scan_header.stamp + ros::Duration(transform_tolerance_s_)));
  geometry_msgs::PoseStamped ps;
  ps.header = h;
  ps.pose = pose.pose.pose;
  path_.header.stamp = h.stamp;
  path_.poses.push_back(ps);
  if (static_cast<int>(path_.poses.size()) > path_max_poses_)
    path_.poses.erase(path_.poses.begin());
  if (path_pub_.getNumSubscribers() > 0) path_pub_.publish(path_);
  if (map_pub_.getNumSubscribers() > 0) map_pub_.publish(mapMarkers(h));
}

visualization_msgs::MarkerArray EkfSlamMapperNode::mapMarkers(const std_msgs::Header& h) const {
  auto make = [&](const std::string& ns, int type, double width, float r, float g, float b) {
    visualization_msgs::Marker m;
    m.header = h;
    m.ns = ns;
    m.type = type;
    m.action = visualization_msgs::Marker::ADD;
    m.pose.orientation.w = 1.0;
    m.scale.x = width;
    m.color.r = r;
    m.color.g = g;
    m.color.b = b;
    m.color.a = 1.0;
    return m;
  };
  visualization_msgs::Marker confirmed =
      make("landmarks", visualization_msgs::Marker::LINE_LIST, 0.06, 0.0f, 0.0f, 0.0f);
  visualization_msgs::Marker fixed =
      make("fixed landmarks", visualization_msgs::Marker::LINE_LIST, 0.08, 0.0f, 0.3f, 0.9f);
  visualization_msgs::Marker tentative =
      make("tentative landmarks", visualization_msgs::Marker::LINE_LIST, 0.03, 0.6f, 0.6f, 0.6f);
  visualization_msgs::Marker bands =
      make("2-sigma", visualization_msgs::Marker::LINE_LIST, 0.02, 0.9f, 0.2f, 0.2f);
  // The EKF's map drawn where the loop closer now puts it (identity without loop closing).
  const slam::LineEkfSlam& ekf = slam_->ekf();
  const math::SE2 correction = slam_->pose() * ekf.pose().inverse();
  auto point = [&correction](const Eigen::Vector2d& p) {
    const Eigen::Vector2d c = correction.transformPoint(p);
    geometry_msgs::Point q;
    q.x = c.x();
    q.y = c.y();
    return q;
  };
  auto add = [&](visualization_msgs::Marker& m, const slam::Landmark& info) {
    for (const auto& pc : info.pieces) {
      m.points.push_back(point(pc.first));
      m.points.push_back(point(pc.second));
    }
  };
  for (int i = 0; i < ekf.numLandmarks(); ++i) {
    const slam::Landmark& info = ekf.landmarkInfo(i);
    add(info.confirmed() ? confirmed : tentative, info);
    if (!info.confirmed()) continue;
    // 2-sigma band of the line's normal offset at the midpoint: the offset of a point at distance
    // u along the line from the foot is rho + u * (alpha error) to first order.
    const slam::Line l = ekf.landmark(i);
    const Eigen::Vector2d n(std::cos(l.alpha_rad), std::sin(l.alpha_rad));
    const Eigen::Vector2d t(-n.y(), n.x()), mid = 0.5 * (info.start_m + info.end_m);
    const double u = t.dot(mid - l.rho_m * n);
    const Eigen::Matrix2d c = ekf.landmarkCovariance(i);
    const double sd = std::sqrt(std::max(0.0, c(0, 0) + 2.0 * u * c(0, 1) + u * u * c(1, 1)));
    bands.points.push_back(point(mid - 2.0 * sd * n));
    bands.points.push_back(point(mid + 2.0 * sd * n));
  }
  for (int k = 0; k < ekf.numFixedLandmarks(); ++k) add(fixed, ekf.fixedLandmark(k).info);
  // The robot's 2-sigma position ellipse.
  visualization_msgs::Marker ellipse =
      make("robot 2-sigma", visualization_msgs::Marker::LINE_STRIP, 0.02, 0.9f, 0.2f, 0.2f);
  const Eigen::Matrix2d pc = ekf.poseCovariance().topLeftCorner<2, 2>();
  const Eigen::LLT<Eigen::Matrix2d> llt(pc + 1e-12 * Eigen::Matrix2d::Identity());
  const Eigen::Matrix2d lower = llt.matrixL();
  for (int k = 0; k <= 36; ++k) {
    const double a = 2.0 * M_PI * k / 36.0;
    const Eigen::Vector2d p = Eigen::Vector2d(ekf.pose().x_m, ekf.pose().y_m) +
                              2.0 * lower * Eigen::Vector2d(std::cos(a), std::sin(a));
    ellipse.points.push_back(point(p));
  }
  visualization_msgs::MarkerArray out;
  for (auto* m : {&confirmed, &fixed, &tentative, &bands, &ellipse})
    if (!m->points.empty()) out.markers.push_back(*m);
  // Clear namespaces that became empty (e.g. no tentative landmarks any more).
  for (auto* m : {&confirmed, &fixed, &tentative, &bands, &ellipse})
    if (m->points.empty()) {
      m->action = visualization_msgs::Marker::DELETE;
      out.markers.push_back(*m);
    }
  return out;
}

bool EkfSlamMapperNode::onSaveMap(SaveMap::Request& req, SaveMap::Response& res) {
  // The reply names the file by its full path (an empty request saves to ~map_file, relative to
  // the node's current directory: $ROS_HOME under roslaunch).
  const std::string path = io::absolutePath(req.path.empty() ? map_file_ : req.path);
  res.success = false;
  // The occupancy grid goes beside it: NAME_grid.yaml and NAME_grid.pgm.
  const std::string grid_yaml =
      (fs::path(path).parent_path() / (fs::path(path).stem().string() + "_grid.yaml")).string();
  const std::string grid_pgm = fs::path(grid_yaml).replace_extension(".pgm").string();
  std::error_code ec;
  for (const std::string& f : {path, grid_yaml, grid_pgm})
    if ((f == path || map_update_interval_s_ > 0.0) && fs::exists(f, ec) && !req.overwrite) {
      res.message = f + " exists; call again with overwrite: true to replace it";
      return true;
    }
  // A copy of the filter is taken under the lock (a few ms even for hundreds of landmarks); the
  // file is written from it on the service thread while scans go on.
  std::unique_ptr<const slam::LineEkfSlam> snapshot;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    snapshot = std::make_unique<const slam::LineEkfSlam>(slam_->ekf());
  }
  try {
    slam::writeLineMapYaml(path, *snapshot);
    res.success = true;
    res.message = "saved " + std::to_string(snapshot->numLandmarks()) + " landmarks and " +
                  std::to_string(snapshot->numFixedLandmarks()) + " fixed landmarks to " + path;
  } catch (const std::exception& e) {
    res.message = e.what();
    return true;
  }
  if (map_update_interval_s_ <= 0.0) return true;
  nav_msgs::OccupancyGrid unused;
  slam::OccupancyGrid grid;
  try {
    if (renderGrid(&unused, &grid)) {
      slam::writeMapServerFiles(grid, grid_yaml);
      res.message += "; the occupancy grid (" + std::to_string(grid.width) + " x " +
                     std::to_string(grid.height) + " cells) to " + grid_yaml + " and its .pgm";
    } else {
      res.message += "; no occupancy grid yet (no scan matched to its lines)";
    }
  } catch (const std::exception& e) {
    res.success = false;
    res.message += "; but the occupancy grid was not saved: " + std::string(e.what());
  }
  return true;
}

void EkfSlamMapperNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  if (scans_ == 0)
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no scan processed yet");
  else
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "mapping");
  const slam::LineEkfSlam& ekf = slam_->ekf();
  int confirmed = 0;
  for (int i = 0; i < ekf.numLandmarks(); ++i) confirmed += ekf.landmarkInfo(i).confirmed();
  stat.add("variant", slam::variantName(config_.ekf.variant));
  stat.add("landmarks (confirmed)", confirmed);
  stat.add("landmarks (in state)", ekf.numLandmarks());
  stat.add("landmarks (anchored or retired)", ekf.numFixedLandmarks());
  stat.add("front end", config_.front_end ? "laser odometry" : "off");
  stat.add("front end: matched scans", slam_->frontEnd().matched());
  stat.add("front end: weak matches (odometry kept)", slam_->frontEnd().weakMatchesRejected());
  stat.add("loop closing", config_.loop_closing ? "on" : "off");
  stat.add("loop closures", slam_->loopCloser().loopClosures());
  stat.add("wide search", config_.loop.wide_search ? "on" : "off");
  stat.add("wide loops confirmed (two edges each)", slam_->loopCloser().wideConfirmed());
  stat.add("wide matches dropped: ambiguous in rotation", slam_->loopCloser().wideAmbiguous());
  stat.add("wide matches dropped: beyond the joined node's window",
           slam_->loopCloser().wideBeyondWindow());
  stat.add("graph nodes", slam_->loopCloser().nodes());
  stat.add("chain edges from the front end (EKF jumped)", slam_->loopCloser().chainEdgesReplaced());
  stat.add("update time last (ms)", last_update_ms_);
  stat.add("update time max (ms)", max_update_ms_);
  stat.add("scans", scans_);
  stat.add("scans skipped (no tf)", tf_.skipped());
  stat.add("scans dropped (older than the last)", stamp_order_.dropped());
  stat.add("scans skipped (update failed)", update_failures_);
  stat.add("segments dropped (bad values)", bad_segments_);
  stat.add("external poses used", external_used_);
  stat.add("external poses rejected", external_rejected_);
  stat.add("resets", resets_);
  stat.add("grid keyframes", static_cast<long>(keyframes_->size()));
  stat.add("grid renders", grid_renders_);
  stat.add("grid render time last (s)", last_grid_s_);
  stat.add("lines without their scan (not in the grid)", scans_without_laser_scan_);
  stat.add("readings taken for no returns below range_max", no_returns_marked_);
}

// The node's main (src/nodes, ros/node_main.h) links this one instance.
template int runNode<EkfSlamMapperNode>(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
