#include "adaptive_perception/ros/condensation_tracker_node.h"

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "adaptive_perception/TrackedObject.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/parameter_docs.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/ros/node_run.h"

namespace adaptive_perception {

namespace {
// The node's own parameters' defaults (the trackers' are in their configs).
constexpr char kTrackerDefaultMode[] = "box";
constexpr double kTrackerMaxRate_hz = 30.0;
}  // namespace

std::vector<config::ParameterDoc> CondensationTrackerNode::parameters() {
  return ros_params::joinRows(
      {{{"mode", "string", kTrackerDefaultMode, "box, condensation, ellipse",
         "box: CONDENSATION over the target's box (colours against the surroundings and a "
         "correlation filter; the tracker for real video); condensation: CONDENSATION + affine "
         "snake (the paper's 3.3); ellipse: the paper's 3.2 alone"}},
       config::describe(tracking::BoxTrackerConfig::fields(), tracking::BoxTrackerConfig()),
       config::describe(tracking::CondensationConfig::fields(), tracking::CondensationConfig()),
       config::describe(tracking::EllipseTrackerConfig::fields(), tracking::EllipseTrackerConfig()),
       {ros_params::wordParameter(
            "color_space", tracking::colorSpaces(), tracking::CondensationConfig().quantizer.space,
            "modes condensation and ellipse: opponent = (B-G, G-R, R+G+B), as in the paper's "
            "later experiments, or rgb"),
        {"dynamics", "string", "", "",
         "YAML of A1, A0, d, B from learn_tracking_dynamics; empty: the default model"},
        {"initial_roi", "list", "[]", "",
         "[x, y, w, h] pixels in the first image; empty: wait for ~set_target or the target topic"},
        {"max_rate_hz", "double", config::formatReal(kTrackerMaxRate_hz), "[0.01, 1000]",
         "images faster than this (by stamp) are skipped"},
        {"publish_overlay", "bool", "true", "",
         "condensation_tracker/overlay (only computed with a subscriber)"},
        ros_params::seedParameter()},
       ros_params::imageIntakeParameters()});
}

CondensationTrackerNode::CondensationTrackerNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : diagnostics_(nh, "condensation_tracker", 1.0, 1000.0) {
  namespace P = ros_params;
  const std::string mode = P::get<std::string>(pnh, "mode", kTrackerDefaultMode);
  if (mode != "box" && mode != "condensation" && mode != "ellipse")
    throw P::ParamError("parameter " + pnh.resolveName("mode") + " = '" + mode +
                        "' must be box, condensation or ellipse");
  mode_ = mode == "box"            ? Mode::kBox
          : mode == "condensation" ? Mode::kCondensation
                                   : Mode::kEllipse;
  P::loadFields(pnh, tracking::BoxTrackerConfig::fields(), &box_config_);
  box_config_.validate();
  tracking::CondensationConfig& c = config_;
  P::loadFields(pnh, tracking::CondensationConfig::fields(), &c);
  c.quantizer.space = P::getWord(pnh, "color_space", tracking::colorSpaces(), c.quantizer.space);
  const std::string dynamics = P::get<std::string>(pnh, "dynamics", "");
  if (!dynamics.empty()) c.dynamics = tracking::Ar2Model::loadYaml(P::resolvePackagePath(dynamics));
  c.validate();
  P::loadFields(pnh, tracking::EllipseTrackerConfig::fields(), &ellipse_config_);
  ellipse_config_.quantizer = c.quantizer;
  ellipse_config_.validate();
  publish_overlay_ = P::get<bool>(pnh, "publish_overlay", true);
  gate_ = ros_conv::ImageGate("condensation_tracker",
                              P::getInRange(pnh, "max_rate_hz", kTrackerMaxRate_hz, 0.01, 1000.0),
                              P::loadImageIntake(pnh));
  seed_ = P::loadSeed(pnh);
  const std::vector<double> roi = P::getNumbers(pnh, "initial_roi", {});
  if (!roi.empty()) {
    std::string why;
    if (roi.size() != 4 || !requestTarget({roi[0], roi[1], roi[2], roi[3]}, &why))
      throw P::ParamError("parameter " + pnh.resolveName("initial_roi") +
                          " must be [x, y, w, h] with w, h >= 4 pixels" +
                          (why.empty() ? "" : ": " + why));
  }

  object_pub_ = nh.advertise<TrackedObject>(ros_topics::kTrackedObject, 10);
  segmentation_pub_ =
      image_transport::ImageTransport(nh).advertise("condensation_tracker/segmentation", 2);
  overlay_pub_ = image_transport::ImageTransport(nh).advertise("condensation_tracker/overlay", 2);
  image_sub_ = image_transport::ImageTransport(nh).subscribe(
      ros_topics::kCameraImage, 2, &CondensationTrackerNode::onImage, this,
      ros_params::imageTransportHints(pnh));
  target_sub_ =
      nh.subscribe("condensation_tracker/target", 2, &CondensationTrackerNode::onTarget, this);
  target_srv_ = nh.advertiseService("condensation_tracker/set_target",
                                    &CondensationTrackerNode::onSetTarget, this);
  diagnostics_.add("tracking", this, &CondensationTrackerNode::diagnose);
  ROS_INFO("condensation_tracker: mode %s, %d samples, colour space %s, %s", mode.c_str(),
           mode_ == Mode::kBox ? box_config_.samples : c.samples,
           tracking::colorSpaceName(c.quantizer.space).c_str(),
           pending_target_ ? "target from ~initial_roi" : "waiting for a target");
}

CondensationTrackerNode::~CondensationTrackerNode() {
  std::printf("condensation_tracker: frames=%ld lost=%ld reacquired=%ld dropped=%ld\n", frames_,
              lost_frames_, reacquired_, gate_.badImages());
  std::fflush(stdout);
}

bool CondensationTrackerNode::requestTarget(const cv::Rect2d& roi, std::string* why) {
  if (!(roi.width >= 4 && roi.height >= 4) || !std::isfinite(roi.x) || !std::isfinite(roi.y)) {
    *why = "the region must be at least 4 x 4 pixels";
    return false;
  }
  // Judged against the last image's size (a target may also come before the first image: it is
  // then judged when that image arrives); a refused target leaves the running track as it was.
  if (!image_size_.empty()) {
    const cv::Rect2d inside = roi & cv::Rect2d(0, 0, image_size_.width, image_size_.height);
    if (inside.width < 4 || inside.height < 4) {
      char buf[160];
      std::snprintf(buf, sizeof(buf),
                    "the region (%.0f, %.0f, %.0f x %.0f) lies outside the %d x %d image", roi.x,
                    roi.y, roi.width, roi.height, image_size_.width, image_size_.height);
      *why = buf;
      return false;
    }
  }
  pending_target_ = roi;
  last_target_ = roi;
  return true;
}

void CondensationTrackerNode::onTarget(const geometry_msgs::PolygonStampedConstPtr& msg) {
  if (msg->polygon.points.empty()) {
    ROS_ERROR("condensation_tracker: target polygon has no point; ignored");
    return;
  }
  const cv::Rect2d box = ros_conv::polygonBox(msg->polygon);
  std::string why;
  if (!requestTarget(box, &why))
    ROS_ERROR("condensation_tracker: target polygon ignored: %s", why.c_str());
}

bool CondensationTrackerNode::onSetTarget(SetTarget::Request& req, SetTarget::Response& res) {
  std::string why;
  res.success =
      requestTarget({static_cast<double>(req.roi.x_offset), static_cast<double>(req.roi.y_offset),
                     static_cast<double>(req.roi.width), static_cast<double>(req.roi.height)},
                    &why);
  res.message = res.success ? "target set on the next image" : why;
  return true;
}

void CondensationTrackerNode::onImage(const sensor_msgs::ImageConstPtr& msg) {
  ros_conv::processGuarded("condensation_tracker", *msg, [&] { processImage(msg); });
}

void CondensationTrackerNode::processImage(const sensor_msgs::ImageConstPtr& msg) {
  cv::Mat bgr;
  bool restart = false;
  if (gate_.accept(*msg, &bgr, &restart) != ros_conv::ImageGate::Result::kProcess) return;
  image_size_ = bgr.size();
  if (restart && last_target_ && !pending_target_) {
    // A looped bag: start again from the last target given, on this image.
    ROS_WARN("condensation_tracker: restarting from the last target given");
    pending_target_ = last_target_;
  }
  if (pending_target_) {
    const cv::Rect2d roi = *pending_target_;
    pending_target_.reset();
    try {  // a new tracker replaces the running one only once it started
      if (mode_ == Mode::kBox) {
        auto next = std::make_unique<tracking::BoxCondensationTracker>(box_config_, seed_);
        next->init(bgr, roi);
        box_ = std::move(next);
      } else if (mode_ == Mode::kEllipse) {
        auto next = std::make_unique<tracking::EllipseTracker>(ellipse_config_);
        next->init(bgr, tracking::Ellipse::inscribed(roi));
        ellipse_ = std::move(next);
      } else {
        auto next = std::make_unique<tracking::CondensationTracker>(config_, seed_);
        next->init(bgr, cv::Rect(roi));
        tracker_ = std::move(next);
      }
      lost_ = false;
      ROS_INFO("condensation_tracker: target at %.0f, %.0f (%.0f x %.0f)", roi.x, roi.y, roi.width,
               roi.height);
    } catch (const std::invalid_argument& e) {
      ROS_ERROR("condensation_tracker: cannot start on the target (%s): %s", e.what(),
                tracker_ || ellipse_ || box_ ? "the running track goes on" : "no track");
    }
    return;
  }
  if (!tracker_ && !ellipse_ && !box_) return;
  TrackedObject out;
  out.header = msg->header;
  out.mode = mode_ == Mode::kBox ? "box" : mode_ == Mode::kEllipse ? "ellipse" : "condensation";
  out.color_space = mode_ == Mode::kBox ? std::string(box_config_.chroma ? "chromaticity" : "rgb")
                                        : tracking::colorSpaceName(config_.quantizer.space);
  tracking::Contour contour;
  cv::Mat segmentation;
  cv::Rect search;
  std::vector<tracking::Contour> sample_contours;
  std::vector<double> sample_weights;
  std::vector<cv::Rect2d> sample_boxes;
  bool lost = false;
  if (box_) {
    const tracking::BoxTrackResult r = box_->track(bgr);
    lost = r.lost;
    out.confidence = r.confidence;
    const cv::Rect2d& q = r.box;
    contour = {
        {q.x, q.y}, {q.x + q.width, q.y}, {q.x + q.width, q.y + q.height}, {q.x, q.y + q.height}};
    search = r.search;
    if (!r.likelihood.empty() && segmentation_pub_.getNumSubscribers() > 0) {
      segmentation = cv::Mat::zeros(bgr.size(), CV_8UC1);
      r.likelihood.convertTo(segmentation(r.search), CV_8U, 255.0);
    }
    sample_boxes = r.samples;
    sample_weights = r.weights;
    out.samples = static_cast<std::uint32_t>(r.samples.size());
  } else if (ellipse_) {
    const tracking::EllipseResult r = ellipse_->track(bgr);
    lost = r.lost;
    out.confidence = r.intersection;
    contour = tracking::ellipseContour(r.ellipse.cx, r.ellipse.cy, r.ellipse.ax, r.ellipse.ay,
                                       config_.contour_points);
  } else {
    const tracking::TrackingResult r = tracker_->track(bgr);
    lost = r.lost;
    out.confidence = r.best.weight;
    contour = r.contour;
    segmentation = r.segmentation;
    sample_contours = r.sample_contours;
    sample_weights = r.weights;
    search = r.roi;
    out.samples = static_cast<std::uint32_t>(r.samples.size());
    for (int k = 0; k < 3; ++k) {
      out.color_mean[k] = r.distribution.mean[k];
      out.color_magnitudes[k] = r.distribution.magnitudes[k];
      for (int j = 0; j < 3; ++j) out.color_axes[3 * k + j] = r.distribution.axes(k, j);
    }
  }
  out.lost = lost;
  for (const auto& p : contour) {
    geometry_msgs::Point32 q;
    q.x = static_cast<float>(p.x());
    q.y = static_cast<float>(p.y());
    out.contour.points.push_back(q);
  }
  const cv::Rect box = cv::Rect(tracking::contourBox(contour)) & cv::Rect(0, 0, bgr.cols, bgr.rows);
  out.box.x_offset = static_cast<std::uint32_t>(std::max(0, box.x));
  out.box.y_offset = static_cast<std::uint32_t>(std::max(0, box.y));
  out.box.width = static_cast<std::uint32_t>(std::max(0, box.width));
  out.box.height = static_cast<std::uint32_t>(std::max(0, box.height));
  std::vector<cv::Point2f> pts;
  for (const auto& p : contour)
    pts.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  if (box_) {  // the box's inscribed ellipse
    out.ellipse_cx = static_cast<float>(box.x + box.width / 2.0);
    out.ellipse_cy = static_cast<float>(box.y + box.height / 2.0);
    out.ellipse_width = static_cast<float>(box.width);
    out.ellipse_height = static_cast<float>(box.height);
    out.ellipse_angle = 0.0f;
  } else if (pts.size() >= 5) {
    const cv::RotatedRect e = cv::fitEllipse(pts);
    out.ellipse_cx = e.center.x;
    out.ellipse_cy = e.center.y;
    out.ellipse_width = e.size.width;
    out.ellipse_height = e.size.height;
    out.ellipse_angle = e.angle * M_PI / 180.0;
  }
  object_pub_.publish(out);
  ++frames_;
  if (lost) {
    ++lost_frames_;
    ROS_WARN_THROTTLE(2.0, "condensation_tracker: target lost; searching");
  } else if (lost_) {
    ++reacquired_;
    ROS_INFO("condensation_tracker: target re-acquired");
  }
  lost_ = lost;
  confidence_ = out.confidence;
  if (!segmentation.empty() && segmentation_pub_.getNumSubscribers() > 0)
    segmentation_pub_.publish(ros_conv::mono8ToImage(segmentation, msg->header));
  if (publish_overlay_ && overlay_pub_.getNumSubscribers() > 0) {
    cv::Mat over = bgr.clone();
    std::vector<cv::Point> poly;
    for (const auto& p : contour)
      poly.emplace_back(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
    if (search.area() > 0) cv::rectangle(over, search, cv::Scalar(200, 0, 200), 1);
    // The samples' snakes, brighter with weight (the best sample is the brightest).
    const double wmax = sample_weights.empty()
                            ? 0.0
                            : *std::max_element(sample_weights.begin(), sample_weights.end());
    for (size_t i = 0; i < sample_boxes.size() && wmax > 0.0; ++i) {
      const double level = 0.25 + 0.75 * sample_weights[i] / wmax;
      if (level < 0.3) continue;  // the faintest would only hide the image
      cv::rectangle(over, cv::Rect(sample_boxes[i]), cv::Scalar(255 * level, 255 * level, 0), 1);
    }
    for (size_t i = 0; i < sample_contours.size() && wmax > 0.0; ++i) {
      if (sample_contours[i].size() < 3) continue;
      const double level = 0.25 + 0.75 * sample_weights[i] / wmax;
      std::vector<cv::Point> s;
      for (const auto& p : sample_contours[i])
        s.emplace_back(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
      cv::polylines(over, s, true, cv::Scalar(255 * level, 255 * level, 0), 1);
    }
    if (!poly.empty())
      cv::polylines(over, poly, true, lost ? cv::Scalar(0, 0, 255) : cv::Scalar(0, 220, 0), 2);
    cv::putText(over, cv::format("%s %.2f", lost ? "LOST" : "tracking", out.confidence), {5, 18},
                cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    overlay_pub_.publish(ros_conv::bgr8ToImage(over, msg->header));
  }
  diagnostics_.tick();
  diagnostics_.update();
}

void CondensationTrackerNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  if (!tracker_ && !ellipse_ && !box_)
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "waiting for a target");
  else if (lost_)
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "target lost");
  else
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "tracking");
  stat.add("frames", frames_);
  stat.add("lost frames", lost_frames_);
  stat.add("re-acquired", reacquired_);
  stat.add("confidence", confidence_);
  stat.add("bad images", gate_.badImages());
}

// The node's main (src/nodes, ros/node_main.h) links this one instance.
template int runNode<CondensationTrackerNode>(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
