#include "adaptive_perception/ros/appearance_localizer_node.h"

#include <geometry_msgs/PoseArray.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>

#include <cmath>
#include <cstdio>

#include "adaptive_perception/PlaceRecognition.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/node_run.h"
#include "adaptive_perception/ros/parameter_docs.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"

namespace adaptive_perception {

namespace {
// The node's own parameters' defaults (the algorithm's are in its two configs).
constexpr char kAppearanceDefaultDatabase[] = "places.sqlite";
constexpr double kAppearanceMaxRate_hz = 5.0, kAppearanceTransformTolerance_s = 0.1;
}  // namespace

std::vector<config::ParameterDoc> AppearanceLocalizerNode::parameters() {
  return ros_params::joinRows(
      {{{"database", "string", kAppearanceDefaultDatabase, "",
         "a place database with SIFT training frames and their poses (train_places --features)"}},
       config::describe(places::RoomClassifierConfig::fields(), places::RoomClassifierConfig()),
       config::describe(localization::AppearanceMclConfig::fields(),
                        localization::AppearanceMclConfig()),
       {{"use_odom", "bool", "true", "",
         "move the particles by odom; else by the training run's average step"},
        {"max_rate_hz", "double", config::formatReal(kAppearanceMaxRate_hz), "[0.01, 1000]",
         "images processed per second of image time at most"},
        {"publish_tf", "bool", "false", "", "broadcast map -> odom (needs odom)"},
        {"transform_tolerance", "double", config::formatReal(kAppearanceTransformTolerance_s),
         "[0, 10]", "map -> odom is stamped this far after its image (s), as amcl does"},
        ros_params::frameParameter("map"),
        ros_params::frameParameter("odom"),
        ros_params::seedParameter()},
       ros_params::imageIntakeParameters()});
}

AppearanceLocalizerNode::AppearanceLocalizerNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : diagnostics_(nh, "appearance_localizer", 0.1, 100.0) {
  namespace P = ros_params;
  const std::string path = P::getName(pnh, "database", kAppearanceDefaultDatabase);
  P::loadFields(pnh, places::RoomClassifierConfig::fields(), &classifier_config_);
  localization::AppearanceMclConfig m;
  P::loadFields(pnh, localization::AppearanceMclConfig::fields(), &m);
  use_odom_ = P::get<bool>(pnh, "use_odom", true);
  const ros_conv::ImageIntakeConfig intake = P::loadImageIntake(pnh);
  gate_ = ros_conv::ImageGate(
      "appearance_localizer",
      P::getInRange(pnh, "max_rate_hz", kAppearanceMaxRate_hz, 0.01, 1000.0), intake);
  localization::OdometryBufferConfig odom_config;
  odom_config.restart_after_back_s = intake.order.restart_after_back_s;
  odom_ = localization::OdometrySync<Frame>(odom_config);
  publish_tf_ = P::get<bool>(pnh, "publish_tf", false);
  transform_tolerance_s_ =
      P::getInRange(pnh, "transform_tolerance", kAppearanceTransformTolerance_s, 0.0, 10.0);
  map_frame_ = P::getFrameId(pnh, "map_frame", ros_topics::kMapFrame);
  odom_frame_ = P::getFrameId(pnh, "odom_frame", ros_topics::kOdomFrame);
  const std::uint64_t seed = P::loadSeed(pnh);

  const places::PlaceDatabase db = places::PlaceDatabase::open(path, true);
  if (db.recoveredJournal())
    ROS_WARN(
        "appearance_localizer: %s: a write that was interrupted (a killed train_places?) "
        "was rolled back; the database is as it was before that write",
        path.c_str());
  classifier_ = std::make_unique<places::RoomClassifier>(classifier_config_);
  classifier_->setFrames(db.loadFrames());
  std::vector<localization::PosedFrame> posed;
  for (const auto& f : classifier_->frames()) {
    if (!f.has_pose)
      throw std::runtime_error(path + ": training frame " + std::to_string(f.image_id) +
                               " has no pose (train from a bag with ground_truth/pose)");
    posed.push_back({math::SE2(f.x_m, f.y_m, f.yaw_rad), classifier_->roomIndex(f.place)});
  }
  // Kept to start the filter again, with the same seed, when a bag loops.
  make_filter_ = [this, posed, m, seed] {
    mcl_ = std::make_unique<localization::AppearanceMcl>(
        posed, static_cast<int>(classifier_->rooms().size()), m, seed);
  };
  make_filter_();

  pose_pub_ =
      nh.advertise<geometry_msgs::PoseWithCovarianceStamped>("appearance_localizer/pose", 5);
  particles_pub_ = nh.advertise<geometry_msgs::PoseArray>("appearance_localizer/particles", 2);
  room_pub_ = nh.advertise<PlaceRecognition>("appearance_localizer/room", 10);
  image_sub_ = image_transport::ImageTransport(nh).subscribe(
      ros_topics::kCameraImage, 2, &AppearanceLocalizerNode::onImage, this,
      ros_params::imageTransportHints(pnh));
  if (use_odom_)
    odom_sub_ = nh.subscribe(ros_topics::kOdom, 50, &AppearanceLocalizerNode::onOdom, this);
  initial_pose_sub_ = nh.subscribe("initialpose", 2, &AppearanceLocalizerNode::onInitialPose, this);
  global_srv_ = nh.advertiseService("global_localization",
                                    &AppearanceLocalizerNode::onGlobalLocalization, this);
  diagnostics_.add("localization", this, &AppearanceLocalizerNode::diagnose);
  ROS_INFO("appearance_localizer: %zu training frames in %zu rooms from %s, %d particles",
           classifier_->frames().size(), classifier_->rooms().size(), path.c_str(), m.particles);
}

AppearanceLocalizerNode::~AppearanceLocalizerNode() {
  std::printf("appearance_localizer: frames=%ld classified=%ld reinitializations=%ld dropped=%ld\n",
              frames_, classified_, reinits_, gate_.badImages());
  std::fflush(stdout);
}

void AppearanceLocalizerNode::onOdom(const nav_msgs::OdometryConstPtr& msg) {
  const auto& p = msg->pose.pose;
  if (!std::isfinite(p.position.x) || !std::isfinite(p.position.y) ||
      !std::isfinite(p.orientation.x) || !std::isfinite(p.orientation.y) ||
      !std::isfinite(p.orientation.z) || !std::isfinite(p.orientation.w)) {
    ROS_WARN_THROTTLE(5.0, "appearance_localizer: odom with a non-finite pose ignored");
    return;
  }
  stepAll(odom_.odometry(msg->header.stamp.toSec(), ros_conv::toSE2(p)));
}

void AppearanceLocalizerNode::stepAll(
    std::vector<localization::OdometrySync<Frame>::Release> released) {
  for (const auto& r : released)
    ros_conv::processGuarded("appearance_localizer", *r.item.msg, [&] { step(r.item, r.pose); });
}

void AppearanceLocalizerNode::onInitialPose(
    const geometry_msgs::PoseWithCovarianceStampedConstPtr& msg) {
  if (msg->header.frame_id != map_frame_) {
    ROS_WARN("appearance_localizer: initial pose in frame '%s' ignored: it must be in '%s'",
             msg->header.frame_id.c_str(), map_frame_.c_str());
    return;
  }
  try {
    const ros_conv::PlanarPoseInput in =
        ros_conv::planarPoseInput(msg->pose, ros_conv::PoseYaw::kRequired);
    mcl_->initGaussian(in.pose, in.cov);
  } catch (const std::invalid_argument& e) {
    ROS_WARN("appearance_localizer: initial pose ignored: %s", e.what());
    return;
  }
  ++initial_poses_;
  ROS_INFO("appearance_localizer: particles set around (%.2f, %.2f) from initialpose",
           msg->pose.pose.position.x, msg->pose.pose.position.y);
}

bool AppearanceLocalizerNode::onGlobalLocalization(std_srvs::Empty::Request&,
                                                   std_srvs::Empty::Response&) {
  mcl_->initGlobal();
  ROS_INFO("appearance_localizer: global localization requested");
  return true;
}

void AppearanceLocalizerNode::onImage(const sensor_msgs::ImageConstPtr& msg) {
  ros_conv::processGuarded("appearance_localizer", *msg, [&] { processImage(msg); });
}

void AppearanceLocalizerNode::processImage(const sensor_msgs::ImageConstPtr& msg) {
  cv::Mat bgr;
  bool restart = false;
  const auto verdict = gate_.accept(*msg, &bgr, &restart);
  const double t = msg->header.stamp.toSec();
  if (restart) {  // a looped bag: the filter starts again as at start-up (same seed, same output)
    make_filter_();
    last_odom_.reset();
    // The held image and the odometry of before the jump go: its pose would move every particle
    // across the map.
    odom_.restart(t);
  }
  if (verdict != ros_conv::ImageGate::Result::kProcess) return;
  if (!use_odom_) {
    step(Frame{msg, bgr}, std::nullopt);
    return;
  }
  // The image waits for the odometry of its own instant (localization/odometry_buffer.h), so that
  // a replay moves the particles by the same steps whatever order the topics arrive in.
  const bool was_matching = odom_.matching();
  auto released = odom_.image(t, Frame{msg, bgr});
  if (was_matching && !odom_.matching())
    ROS_WARN(
        "appearance_localizer: no odom stamped at or after the last images (none published, "
        "or on another clock): images are taken without waiting for it until it comes");
  stepAll(std::move(released));  // each step under its own guard
}

void AppearanceLocalizerNode::step(const Frame& frame, const std::optional<math::SE2>& odom_pose) {
  const sensor_msgs::ImageConstPtr& msg = frame.msg;
  const cv::Mat& bgr = frame.bgr;
  const auto sims = classifier_->frameSimilarities(classifier_->extract(bgr),
                                                   classifier_config_.index.candidates);
  std::optional<math::SE2> delta;
  if (odom_pose && last_odom_) delta = math::between(*last_odom_, *odom_pose);
  const localization::AppearanceEstimate e = mcl_->step(delta, sims);
  last_odom_ = odom_pose;  // none: the next delta must not span the gap as well
  ++frames_;
  reinits_ += e.reinitialized;
  stable_ = e.stable;
  diagnostics_.tick();

  std_msgs::Header h = msg->header;
  h.frame_id = map_frame_;
  pose_pub_.publish(ros_conv::toPoseWithCovariance(e.pose, e.covariance, h));
  if (particles_pub_.getNumSubscribers() > 0) {
    geometry_msgs::PoseArray pa;
    pa.header = h;
    for (const math::SE2& p : mcl_->particles()) pa.poses.push_back(ros_conv::toPose(p));
    particles_pub_.publish(pa);
  }
  PlaceRecognition room;
  room.header = msg->header;
  room.route_frame = -1;  // no route filter here
  room.method = "sift_mcl";
  room.places = classifier_->rooms();
  room.belief = e.room_weights;
  room.images = 1;
  if (e.unknown_room) {
    room.place = "unknown";
  } else if (e.room < 0) {
    room.place = "not classified";
  } else {
    room.place = classifier_->rooms()[e.room];
    room.confidence = e.room_weights[e.room];
    ++classified_;
  }
  last_room_ = room.place;
  room_pub_.publish(room);
  if (publish_tf_ && odom_pose) {
    geometry_msgs::TransformStamped t = ros_conv::toTransform(
        ros_conv::mapToOdom(e.pose, world::planarToIsometry(*odom_pose)), map_frame_, odom_frame_,
        msg->header.stamp + ros::Duration(transform_tolerance_s_));
    tf_.sendTransform(t);
  }
  diagnostics_.update();
}

void AppearanceLocalizerNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  if (stable_)
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "stable");
  else
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "unstable: frames not classified");
  stat.add("frames", frames_);
  stat.add("classified", classified_);
  stat.add("re-initialisations", reinits_);
  stat.add("initial poses taken", initial_poses_);
  stat.add("images dropped (bad)", gate_.badImages());
  stat.add("images without odom at their stamp", odom_.unmatched());
  stat.add("last room", last_room_);
}

// The node's main (src/nodes, ros/node_main.h) links this one instance.
template int runNode<AppearanceLocalizerNode>(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
