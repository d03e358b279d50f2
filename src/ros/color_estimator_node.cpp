#include "adaptive_perception/ros/color_estimator_node.h"

#include <filesystem>

#include "adaptive_perception/ColorModel.h"
#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/io/atomic_file.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/parameter_docs.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/ros/node_run.h"

namespace adaptive_perception {

namespace fs = std::filesystem;

namespace {
// The node's own parameters' defaults (the algorithm's are in color::ColorEstimatorConfig, the
// observation noise's and the mixing's too).
constexpr double kColorTfTimeout_s = 0.1;
}  // namespace

std::vector<config::ParameterDoc> ColorEstimatorNode::parameters() {
  namespace P = ros_params;
  const color::ColorEstimatorConfig c;
  return P::joinRows(
      {config::describe(color::ColorEstimatorConfig::fields(), c),
       {P::wordParameter("observation_noise", color::observationNoises(), c.model.observation_noise,
                         "noise of an image's colour mean: pixel (nu, as eq. 5) or "
                         "pixel_over_count (nu / n + ~observation_noise_floor_var)"),
        P::wordParameter("mixing", color::modeMixings(), c.switching.mixing,
                         "best_mode: only the mode that best explains the image is updated (the "
                         "paper); imm")},
       ros_conv::FieldCameraInput::parameters(kColorTfTimeout_s, "map -> camera")});
}

ColorEstimatorNode::ColorEstimatorNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : input_("color_estimator", pnh, kColorTfTimeout_s),
      diagnostics_(nh, "color_estimator", 0.5, 100.0, &mutex_) {
  namespace P = ros_params;
  P::loadFields(pnh, color::ColorEstimatorConfig::fields(), &config_);
  config_.model.observation_noise = P::getWord(pnh, "observation_noise", color::observationNoises(),
                                               config_.model.observation_noise);
  config_.switching.mixing =
      P::getWord(pnh, "mixing", color::modeMixings(), config_.switching.mixing);
  config_.validate();

  model_pub_ = nh.advertise<adaptive_perception::ColorModel>("color_estimator/color_model", 5);
  classified_pub_ = image_transport::ImageTransport(nh).advertise("color_estimator/classified", 2);
  classified_color_pub_ =
      image_transport::ImageTransport(nh).advertise("color_estimator/classified_color", 2);
  input_.subscribe(nh, &ColorEstimatorNode::onImage, &ColorEstimatorNode::onCameraInfo, this);
  ros::NodeHandle service_nh = service_queue_.handle(pnh);
  reset_srv_ = service_nh.advertiseService("reset", &ColorEstimatorNode::onReset, this);
  save_srv_ = service_nh.advertiseService("save_prior", &ColorEstimatorNode::onSavePrior, this);

  diagnostics_.add("estimator", this, &ColorEstimatorNode::diagnose);

  reconfigure_ =
      std::make_unique<dynamic_reconfigure::Server<adaptive_perception::ColorEstimatorConfig>>(
          reconfigure_mutex_, service_nh);
  adaptive_perception::ColorEstimatorConfig initial;
  initial.drift_std_per_sqrt_s = config_.model.drift_std_per_sqrt_s;
  initial.unknown_mahalanobis = config_.model.unknown_mahalanobis;
  initial.mode_stay_probability = config_.switching.mode_stay_probability;
  initial.lut_rebuild_sigma = config_.lut_rebuild_sigma;
  reconfigure_->updateConfig(initial);
  reconfigure_->setCallback([this](adaptive_perception::ColorEstimatorConfig& c, uint32_t level) {
    onReconfigure(c, level);
  });
  ROS_INFO("color_estimator: %s", input_.priorsSummary().c_str());
}

namespace {

/// `c` showing the values of `config` (what dynamic_reconfigure reports back as in force).
void showColorConfig(const color::ColorEstimatorConfig& config,
                adaptive_perception::ColorEstimatorConfig* c) {
  c->drift_std_per_sqrt_s = config.model.drift_std_per_sqrt_s;
  c->unknown_mahalanobis = config.model.unknown_mahalanobis;
  c->mode_stay_probability = config.switching.mode_stay_probability;
  c->lut_rebuild_sigma = config.lut_rebuild_sigma;
}

}  // namespace

void ColorEstimatorNode::onReconfigure(adaptive_perception::ColorEstimatorConfig& c, uint32_t) {
  std::lock_guard<std::mutex> lock(mutex_);
  // dynamic_reconfigure's min/max clamp lets NaN through: the whole new set is validated before
  // any of it is taken, and a refused set leaves every value as it was (and says so in the reply).
  color::ColorEstimatorConfig next = config_;
  next.model.drift_std_per_sqrt_s = c.drift_std_per_sqrt_s;
  next.model.unknown_mahalanobis = c.unknown_mahalanobis;
  next.switching.mode_stay_probability = c.mode_stay_probability;
  next.lut_rebuild_sigma = c.lut_rebuild_sigma;
  try {
    next.validate();
  } catch (const std::exception& e) {
    ROS_ERROR("color_estimator: reconfigure refused, every setting stays as it was: %s", e.what());
    showColorConfig(config_, &c);
    return;
  }
  const bool gate_changed = next.model.unknown_mahalanobis != config_.model.unknown_mahalanobis;
  config_ = next;
  if (!estimator_) return;
  if (gate_changed) {
    estimator_
        .reset();  // the gate is compiled into the table: rebuild from the priors on the next image
    ROS_INFO(
        "color_estimator: unknown_mahalanobis changed: the estimator restarts from its priors");
    return;
  }
  try {
    estimator_->filter().setDrift(config_.model.drift_std_per_sqrt_s);
    estimator_->filter().setConfig(config_.switching);
    estimator_->setLutRebuildSigma(config_.lut_rebuild_sigma);
  } catch (const std::exception& e) {  // validated above; a failure here is a bug, not a crash
    ROS_ERROR("color_estimator: reconfigure failed (%s): the estimator restarts from its priors",
              e.what());
    estimator_.reset();
  }
}

void ColorEstimatorNode::onCameraInfo(const sensor_msgs::CameraInfoConstPtr& msg) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (input_.camera().onCameraInfo(*msg)) estimator_.reset();
}

bool ColorEstimatorNode::ensureEstimator(int width, int height) {
  if (!input_.readyFor(width, height)) return false;
  if (!estimator_)
    estimator_ = std::make_unique<color::ColorEstimator>(input_.field(), input_.camera().camera(),
                                                         input_.priors(), config_);
  return true;
}

void ColorEstimatorNode::onImage(const sensor_msgs::ImageConstPtr& msg) {
  cv::Mat yuv;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // An image a little older than the last is dropped (ImageGate); time really going back resets
    // the model (ColorEstimator::process).
    if (!input_.gate().admit(*msg, &yuv)) return;
  }
  const std::optional<Eigen::Isometry3d> pose =
      input_.tf().transform(input_.mapFrame(), msg->header.frame_id, msg->header.stamp, "image");
  if (!pose) {
    classifyWithoutPose(*msg, yuv);
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  color::ColorEstimator::Result r;
  try {
    if (!ensureEstimator(yuv.cols, yuv.rows)) return;
    r = estimator_->process(msg->header.stamp.toSec(), input_.camera().rectify(yuv), *pose);
  } catch (const std::exception& e) {  // no exception leaves a callback
    ROS_ERROR_THROTTLE(10.0, "color_estimator: frame dropped: %s", e.what());
    input_.countBadImage();
    return;
  }
  if (r.time_reset)
    ROS_WARN("color_estimator: time went backwards (bag looped?): filter reset to its priors");
  last_log_likelihood_ = r.log_likelihood;
  ++frames_;
  diagnostics_.tick();

  std_msgs::Header model_header = msg->header;
  model_header.frame_id = input_.mapFrame();
  const adaptive_perception::ColorModel model =
      ros_conv::toColorModel(estimator_->filter(), model_header);
  model_pub_.publish(model);
  classified_pub_.publish(ros_conv::mono8ToImage(r.classified, msg->header));
  if (classified_color_pub_.getNumSubscribers() > 0)
    classified_color_pub_.publish(
        ros_conv::bgr8ToImage(color::colorizeLabels(r.classified), msg->header));
  diagnostics_.update();
}

void ColorEstimatorNode::classifyWithoutPose(const sensor_msgs::Image& msg, const cv::Mat& yuv) {
  color::FieldSegmentationConfig config;
  cv::Mat rectified;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!config_.pose_free) return;
    config = config_.segmentation;
    try {
      rectified = input_.camera().rectify(yuv);  // as the pose-driven path classifies
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(10.0, "color_estimator: frame dropped: %s", e.what());
      input_.countBadImage();
      return;
    }
  }
  color::FieldSegmentation seg;  // segmented unlocked: services and camera_info answer meanwhile
  try {
    seg = color::segmentFieldYuv(rectified, config);
  } catch (const std::exception& e) {  // no exception leaves a callback
    ROS_ERROR_THROTTLE(10.0, "color_estimator: frame dropped: %s", e.what());
    std::lock_guard<std::mutex> lock(mutex_);
    input_.countBadImage();
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (pose_free_frames_++ == 0)
    ROS_INFO("color_estimator: no camera pose in tf yet: classifying without one (pose_free)");
  diagnostics_.tick();
  classified_pub_.publish(ros_conv::mono8ToImage(seg.labels, msg.header));
  if (classified_color_pub_.getNumSubscribers() > 0)
    classified_color_pub_.publish(
        ros_conv::bgr8ToImage(color::colorizeLabels(seg.labels), msg.header));
  diagnostics_.update();
}

bool ColorEstimatorNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (estimator_) estimator_->reset();
  res.success = true;
  res.message = "colour model reset to its priors";
  ROS_INFO("color_estimator: %s", res.message.c_str());
  return true;
}

bool ColorEstimatorNode::onSavePrior(SavePrior::Request& req, SavePrior::Response& res) {
  std::lock_guard<std::mutex> lock(mutex_);
  res.success = false;
  if (!estimator_) {
    res.message = "no image processed yet: nothing to save";
    return true;
  }
  if (req.path.empty()) {
    res.message = "path is empty";
    return true;
  }
  const std::string path = io::absolutePath(req.path);  // the reply names the full path
  std::error_code ec;
  if (fs::exists(path, ec) && !req.overwrite) {
    res.message = path + " exists; call again with overwrite: true to replace it";
    return true;
  }
  const color::ColorFilter& a = estimator_->filter().active();
  color::LightingPrior p;
  p.name = req.name.empty() ? fs::path(path).stem().string() : req.name;
  for (auto c : config_.model.classes) p.color_names.push_back(world::colorClassName(c));
  p.mean = a.mean();
  p.cov = a.cov();
  p.pixel_noise_var = a.pixelNoiseVar();
  try {
    p.saveYaml(path);
    res.success = true;
    res.message = "saved the posterior of mode '" +
                  estimator_->filter().modeName(estimator_->filter().activeMode()) + "' to " + path;
  } catch (const std::exception& e) {
    res.message = e.what();
  }
  return true;
}

void ColorEstimatorNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  if (!estimator_) {
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                 pose_free_frames_ > 0 ? "classifying without a camera pose (pose_free)"
                                       : "no image processed yet");
  } else {
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "estimating");
    stat.add("active mode", estimator_->filter().modeName(estimator_->filter().activeMode()));
    stat.add("lookup table rebuilds", estimator_->lutRebuilds());
  }
  stat.add("frames", frames_);
  stat.add("frames classified without a pose", pose_free_frames_);
  input_.diagnose(stat);
  stat.add("last log likelihood", last_log_likelihood_);
}

// The node's main (src/nodes, ros/node_main.h) links this one instance.
template int runNode<ColorEstimatorNode>(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
