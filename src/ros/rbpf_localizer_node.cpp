#include "adaptive_perception/ros/rbpf_localizer_node.h"

#include <geometry_msgs/PoseArray.h>
#include <malloc.h>
#include <tf2/exceptions.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/parameter_docs.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/ros/node_run.h"

namespace adaptive_perception {

namespace fs = std::filesystem;
using ros_params::ParamError;

namespace {

/// The heap one particle takes (its lighting filter keeps its own copy of the priors), measured
/// by building one (glibc's allocator statistics).
std::size_t particleBytes(const std::vector<color::LightingPrior>& priors,
                          const localization::RbpfConfig& c) {
  const std::size_t before = ::mallinfo2().uordblks;
  const auto one = std::make_unique<localization::Particle>(localization::Particle{
      math::SE2(), color::SwitchingColorFilter(priors, c.model, c.switching), 0.0});
  return sizeof(localization::Particle) + (::mallinfo2().uordblks - before);
}

/// Refuses a particle count whose filter would not fit in half of this machine's memory (the
/// particles exist twice while resampling), naming the estimate and the largest count that fits.
void checkParticleMemory(const ros::NodeHandle& pnh,
                         const std::vector<color::LightingPrior>& priors,
                         const localization::RbpfConfig& c) {
  const double per_particle = static_cast<double>(particleBytes(priors, c));
  const double physical =
      static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGESIZE));
  const double need = 2.0 * per_particle * c.particles;
  if (physical > 0 && need > 0.5 * physical) {
    char buf[320];
    std::snprintf(buf, sizeof(buf),
                  "parameter %s = %d would take about %.1f GB (%.1f kB a particle, twice while "
                  "resampling); this machine has %.1f GB: at most %.0f particles fit in half of it",
                  pnh.resolveName("particles").c_str(), c.particles, need / 1e9, per_particle / 1e3,
                  physical / 1e9, 0.25 * physical / per_particle);
    throw ros_params::ParamError(buf);
  }
}

}  // namespace

namespace {
// The node's own parameters' defaults (the algorithm's are in localization::RbpfConfig).
const std::vector<double> kRbpfInitialPoseStd = {0.2, 0.2, 0.17};
constexpr double kRbpfTransformTolerance_s = 0.1, kRbpfTfTimeout_s = 0.1;

}  // namespace

std::vector<config::ParameterDoc> RbpfLocalizerNode::parameters() {
  return ros_params::joinRows(
      {config::describe(localization::RbpfConfig::fields(), localization::RbpfConfig()),
       {{"threads", "int", "0", "[0, 256]", "threads for the particles (0: all cores)"},
        ros_params::seedParameter(),
        {"initial_pose", "list", "[]", "", "[x_m, y_m, yaw_rad]; empty: global localization"},
        {"initial_pose_std", "list", config::formatList(kRbpfInitialPoseStd), "",
         "its standard deviations (m, m, rad)"},
        ros_params::frameParameter("odom"),
        ros_params::frameParameter("base"),
        {"publish_tf", "bool", "true", "", "broadcast map -> odom"},
        {"transform_tolerance_s", "double", config::formatReal(kRbpfTransformTolerance_s),
         "[0, 10]", "map -> odom is future-dated by this (s), as amcl does"}},
       ros_conv::FieldCameraInput::parameters(kRbpfTfTimeout_s, "odom -> base_link -> camera")});
}

RbpfLocalizerNode::RbpfLocalizerNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : input_("rbpf_localizer", pnh, kRbpfTfTimeout_s),
      diagnostics_(nh, "rbpf_localizer", 0.5, 100.0, &mutex_) {
  namespace P = ros_params;
  localization::RbpfConfig& c = config_;
  P::loadFields(pnh, localization::RbpfConfig::fields(), &c);
  const int threads = P::getInRange(pnh, "threads", 0, 0, 256);
  c.threads = threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
  c.seed = P::loadSeed(pnh);

  checkParticleMemory(pnh, input_.priors(), c);

  math::SE2 initial;
  if (P::loadInitialPose(pnh, kRbpfInitialPoseStd, &initial, &initial_pose_cov_))
    pending_pose_ = configured_pose_ = std::make_pair(initial, initial_pose_cov_);

  odom_frame_ = P::getFrameId(pnh, "odom_frame", ros_topics::kOdomFrame);
  base_frame_ = P::getFrameId(pnh, "base_frame", ros_topics::kBaseFrame);
  publish_tf_ = P::get<bool>(pnh, "publish_tf", true);
  transform_tolerance_s_ =
      P::getInRange(pnh, "transform_tolerance_s", kRbpfTransformTolerance_s, 0.0, 10.0);
  try {
    config_.validate();
  } catch (const std::invalid_argument& e) {
    throw ParamError(std::string("rbpf_localizer parameters: ") + e.what());
  }

  pose_pub_ = nh.advertise<geometry_msgs::PoseWithCovarianceStamped>("rbpf_localizer/pose", 5);
  particles_pub_ = nh.advertise<geometry_msgs::PoseArray>("rbpf_localizer/particles", 2);
  model_pub_ = nh.advertise<adaptive_perception::ColorModel>("rbpf_localizer/color_model", 5);
  classified_pub_ = image_transport::ImageTransport(nh).advertise("rbpf_localizer/classified", 2);
  classified_color_pub_ =
      image_transport::ImageTransport(nh).advertise("rbpf_localizer/classified_color", 2);
  input_.subscribe(nh, &RbpfLocalizerNode::onImage, &RbpfLocalizerNode::onCameraInfo, this);
  initial_pose_sub_ = nh.subscribe("initialpose", 1, &RbpfLocalizerNode::onInitialPose, this);
  global_srv_ = service_queue_.handle(nh).advertiseService(
      "global_localization", &RbpfLocalizerNode::onGlobalLocalization, this);

  diagnostics_.add("localizer", this, &RbpfLocalizerNode::diagnose);
  ROS_INFO("rbpf_localizer: %d particles on %d thread(s), %s, %s start", c.particles, c.threads,
           input_.priorsSummary().c_str(), pending_pose_ ? "tracking" : "global");
}

void RbpfLocalizerNode::onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!input_.camera().onCameraInfo(*msg) || !rbpf_) return;
  ROS_WARN("rbpf_localizer: camera model changed: the filter restarts around its estimate");
  const auto e = rbpf_->estimate();
  pending_pose_ = std::make_pair(e.pose, e.covariance + Eigen::Matrix3d::Identity() * 1e-4);
  rbpf_.reset();
}

std::unique_ptr<localization::RbpfLocalizer> RbpfLocalizerNode::newLocalizer() const {
  return std::make_unique<localization::RbpfLocalizer>(input_.field(), input_.camera().camera(),
                                                       input_.priors(), config_);
}

bool RbpfLocalizerNode::ensureLocalizer(int width, int height) {
  if (!input_.readyFor(width, height)) return false;
  if (!rbpf_) {
    rbpf_ = newLocalizer();
    if (pending_pose_) rbpf_->initGaussian(pending_pose_->first, pending_pose_->second);
    pending_pose_.reset();
    last_odom_.reset();
  }
  return true;
}

void RbpfLocalizerNode::onImage(const sensor_msgs::ImageConstPtr& msg) {
  cv::Mat yuv;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // An image a little older than the last is dropped (ImageGate); time really going back restarts
    // below.
    if (!input_.gate().admit(*msg, &yuv)) return;
  }
  const std::optional<ros_conv::OdomAndMount> tf = input_.tf().odomAndMount(
      odom_frame_, base_frame_, msg->header.frame_id, msg->header.stamp, "image");
  if (!tf) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (!ensureLocalizer(yuv.cols, yuv.rows)) return;
  const Eigen::Isometry3d odom = tf->odom_to_base;
  double dt_s = 0.0;
  math::SE2 delta;
  if (last_odom_) {
    dt_s = (msg->header.stamp - last_stamp_).toSec();
    if (dt_s < 0.0) {
      ROS_WARN(
          "rbpf_localizer: time went backwards by %.3f s (bag looped?): starting again as "
          "at start-up (%s)",
          -dt_s, configured_pose_ ? "~initial_pose" : "global localization");
      // A new filter, not re-spread particles: the same seed and frame count as at start-up, so a
      // replayed bag gives the same estimates.
      rbpf_ = newLocalizer();
      if (configured_pose_) rbpf_->initGaussian(configured_pose_->first, configured_pose_->second);
      ++resets_;
      dt_s = 0.0;
    } else {
      delta = world::isometryToPlanar(last_odom_->inverse() * odom);
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  try {
    last_ = rbpf_->step(delta, dt_s, input_.camera().rectify(yuv), tf->base_to_sensor);
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(10.0, "rbpf_localizer: frame dropped: %s", e.what());
    input_.countBadImage();
    return;
  }
  last_compute_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!std::isnan(last_.relocalization_score)) last_check_score_ = last_.relocalization_score;
  if (last_.relocalized) {
    ++relocalizations_;
    if (last_.global_search_restarted)
      ROS_WARN(
          "rbpf_localizer: the relocalization check found the particles lost (a pose of its pool "
          "beat them by %.2f); global search restarted",
          last_.relocalization_score);
    else
      ROS_WARN(
          "rbpf_localizer: the relocalization check found the particles lost (a pose of its pool "
          "beat them by %.2f); part of them redrawn from its poses",
          last_.relocalization_score);
  }
  if (last_.second_draw)
    ROS_INFO(
        "rbpf_localizer: the global search's second draw replaced part of the particles (its best "
        "pose minus theirs: %.2f)",
        last_.relocalization_score);
  if (last_.mirror_flipped) {
    ++mirror_flips_;
    ROS_WARN(
        "rbpf_localizer: moved the particles to their point mirrors (the goal and beacon "
        "colours favoured the other half of the field by %.2f)",
        -last_.mirror_evidence);
  }
  last_odom_ = odom;
  last_stamp_ = msg->header.stamp;
  ++frames_;
  diagnostics_.tick();
  publish(msg->header, odom, yuv);
  diagnostics_.update();
}

void RbpfLocalizerNode::publish(const std_msgs::Header& image_header,
                                const Eigen::Isometry3d& odom_to_base, const cv::Mat& yuv) {
  const auto e = rbpf_->estimate();
  std_msgs::Header h = image_header;
  h.frame_id = input_.mapFrame();
  pose_pub_.publish(ros_conv::toPoseWithCovariance(e.pose, e.covariance, h));
  if (particles_pub_.getNumSubscribers() > 0) {
    geometry_msgs::PoseArray pa;
    pa.header = h;
    for (const auto& p : rbpf_->particles()) pa.poses.push_back(ros_conv::toPose(p.pose));
    particles_pub_.publish(pa);
  }
  if (publish_tf_) {
    // map -> odom = (map -> base) * (odom -> base)^-1, future-dated by the tolerance as amcl does.
    tf_broadcaster_.sendTransform(ros_conv::toTransform(
        ros_conv::mapToOdom(e.pose, odom_to_base), input_.mapFrame(), odom_frame_,
        image_header.stamp + ros::Duration(transform_tolerance_s_)));
  }
  const color::SwitchingColorFilter& lighting = rbpf_->best().lighting;
  model_pub_.publish(ros_conv::toColorModel(lighting, h));
  if (classified_pub_.getNumSubscribers() > 0 || classified_color_pub_.getNumSubscribers() > 0) {
    lut_.update(lighting.active().classifier());
    cv::Mat labels;
    lut_.lut().classifyYuv(yuv, &labels);
    if (classified_pub_.getNumSubscribers() > 0)
      classified_pub_.publish(ros_conv::mono8ToImage(labels, image_header));
    if (classified_color_pub_.getNumSubscribers() > 0)
      classified_color_pub_.publish(
          ros_conv::bgr8ToImage(color::colorizeLabels(labels), image_header));
  }
}

void RbpfLocalizerNode::onInitialPose(const geometry_msgs::PoseWithCovarianceStampedConstPtr& msg) {
  // rviz sends x, y variance 0.25 and yaw 0.068; a message with no covariance at all (zeros) gets
  // ~initial_pose_std. Anything else is read as every node reads a pose input, and refused when
  // broken.
  geometry_msgs::PoseWithCovariance input = msg->pose;
  if (ros_conv::planarCovariance(input).isZero(0.0)) {
    input.covariance[0] = initial_pose_cov_(0, 0);
    input.covariance[7] = initial_pose_cov_(1, 1);
    input.covariance[35] = initial_pose_cov_(2, 2);
  }
  ros_conv::PlanarPoseInput in;
  try {
    in = ros_conv::planarPoseInput(input, ros_conv::PoseYaw::kRequired);
  } catch (const std::invalid_argument& e) {
    ROS_ERROR("rbpf_localizer: initialpose ignored: %s", e.what());
    return;
  }
  Eigen::Isometry3d pose = ros_conv::toIsometry(msg->pose.pose);
  const std::string& map_frame = input_.mapFrame();
  if (!msg->header.frame_id.empty() && msg->header.frame_id != map_frame) {
    try {
      pose =
          ros_conv::toIsometry(input_.tf()
                                   .buffer()
                                   .lookupTransform(map_frame, msg->header.frame_id, ros::Time(0))
                                   .transform) *
          pose;
    } catch (const tf2::TransformException& e) {
      ROS_ERROR("rbpf_localizer: initialpose in frame '%s' ignored: %s",
                msg->header.frame_id.c_str(), e.what());
      return;
    }
  }
  const math::SE2 p = world::isometryToPlanar(pose);
  const Eigen::Matrix3d& cov = in.cov;
  std::lock_guard<std::mutex> lock(mutex_);
  ROS_INFO("rbpf_localizer: initial pose (%.2f m, %.2f m, %.1f deg)", p.x_m, p.y_m,
           p.yaw_rad * 180.0 / M_PI);
  try {
    if (rbpf_)
      rbpf_->initGaussian(p, cov);
    else
      pending_pose_ = std::make_pair(p, cov);
  } catch (const std::exception& e) {  // planarPoseInput checked it: a failure here is a bug
    ROS_ERROR("rbpf_localizer: initialpose ignored: %s", e.what());
    return;
  }
  ++resets_;
}

bool RbpfLocalizerNode::onGlobalLocalization(std_srvs::Empty::Request&,
                                             std_srvs::Empty::Response&) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (rbpf_) rbpf_->initUniform();
  pending_pose_.reset();
  ++resets_;
  ROS_INFO("rbpf_localizer: global localization: particles spread over the field");
  return true;
}

void RbpfLocalizerNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  if (!rbpf_) {
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no image processed yet");
  } else {
    const auto e = rbpf_->estimate();
    if (e.cluster_weight < 0.5)
      stat.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                   "not converged: the main cluster holds less than half the weight");
    else
      stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "localized");
    stat.add("particles", rbpf_->particles().size());
    stat.add("effective sample size", last_.effective_sample_size);
    stat.add("main cluster weight", e.cluster_weight);
    stat.add("spread of all particles (m)", e.spread_m);
    stat.add("position std of the estimate (m)",
             std::sqrt(e.covariance.topLeftCorner<2, 2>().trace()));
    stat.add("relocalizations", relocalizations_);
    stat.add("last relocalization check: best search pose minus best particle", last_check_score_);
    stat.add("mirror flips", mirror_flips_);
    stat.add("mirror test: evidence for the other half", last_.mirror_evidence);
    stat.add("compute time of the last frame (s)", last_compute_s_);
    stat.add("lighting mode", rbpf_->best().lighting.modeName(rbpf_->best().lighting.activeMode()));
  }
  stat.add("frames", frames_);
  input_.diagnose(stat);
  stat.add("re-initialisations", resets_);
}

// The node's main (src/nodes, ros/node_main.h) links this one instance.
template int runNode<RbpfLocalizerNode>(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
