#include "adaptive_perception/ros/line_extractor_node.h"

#include <cmath>

#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/parameter_docs.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/ros/node_run.h"

namespace adaptive_perception {

visualization_msgs::MarkerArray lineMarkers(const LineSegmentArray& lines, const std::string& ns,
                                            float r, float g, float b) {
  visualization_msgs::Marker m;
  m.header = lines.header;
  m.ns = ns;
  m.id = 0;
  m.type = visualization_msgs::Marker::LINE_LIST;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = 0.08;
  m.color.r = r;
  m.color.g = g;
  m.color.b = b;
  m.color.a = 1.0;
  for (const auto& s : lines.segments) {
    m.points.push_back(s.start);
    m.points.push_back(s.end);
  }
  visualization_msgs::MarkerArray out;
  out.markers.push_back(m);
  return out;
}

namespace {

/// `cfg` showing the settings of `c` (what dynamic_reconfigure reports as in force).
void showLineConfig(const laser::LineExtractionConfig& c,
                adaptive_perception::LineExtractorConfig* cfg) {
  cfg->split_threshold_m = c.split_threshold_m;
  cfg->min_points = c.min_points;
  cfg->min_length_m = c.min_length_m;
  cfg->max_gap_m = c.max_gap_m;
  cfg->breakpoint_lambda_rad = c.breakpoint_lambda_rad;
  cfg->merge_collinear = c.merge_collinear;
  cfg->split_method = laser::splitMethods().name(c.split_method);
}

}  // namespace

std::vector<config::ParameterDoc> LineExtractorNode::parameters() {
  return ros_params::joinRows(
      {config::describe(laser::LineExtractionConfig::fields(), laser::LineExtractionConfig()),
       {ros_params::wordParameter(
            "split_method", laser::splitMethods(), laser::LineExtractionConfig().split_method,
            "recursive: Table 2's linear farthest-point scan; hull_tree: O(log^2 n) queries over "
            "convex hulls, the same output"),
        ros_params::stampOrderParameter()}});
}

LineExtractorNode::LineExtractorNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : diagnostics_(nh, "line_extractor", 1.0, 1000.0) {
  namespace P = ros_params;
  laser::LineExtractionConfig c;
  P::loadFields(pnh, laser::LineExtractionConfig::fields(), &c);
  c.split_method = P::getWord(pnh, "split_method", laser::splitMethods(), c.split_method);
  extractor_.setConfig(c);
  stamp_order_ = ros_conv::StampOrder("line_extractor", "scan", P::loadStampOrder(pnh));
  lines_pub_ = nh.advertise<LineSegmentArray>("lines", 10);
  markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("lines/markers", 2);
  // Every scan is worth its lines to the mapper: 20 scans ride out a 2 s stall at 10 Hz, and keep
  // the delay short when scans come faster than they can be taken (as the mapper's queue).
  scan_sub_ = nh.subscribe(ros_topics::kScan, 20, &LineExtractorNode::onScan, this);
  reconfigure_ =
      std::make_unique<dynamic_reconfigure::Server<adaptive_perception::LineExtractorConfig>>(
          reconfigure_mutex_, pnh);
  adaptive_perception::LineExtractorConfig initial;
  showLineConfig(c, &initial);
  reconfigure_->updateConfig(initial);
  reconfigure_->setCallback([this](adaptive_perception::LineExtractorConfig& cfg, uint32_t level) {
    onReconfigure(cfg, level);
  });
}

void LineExtractorNode::onReconfigure(adaptive_perception::LineExtractorConfig& cfg, uint32_t) {
  std::lock_guard<std::mutex> lock(mutex_);
  laser::LineExtractionConfig c = extractor_.config();
  c.split_threshold_m = cfg.split_threshold_m;
  c.min_points = cfg.min_points;
  c.min_length_m = cfg.min_length_m;
  c.max_gap_m = cfg.max_gap_m;
  c.breakpoint_lambda_rad = cfg.breakpoint_lambda_rad;
  c.merge_collinear = cfg.merge_collinear;
  try {  // setConfig validates the whole set before taking any of it
    c.split_method = laser::parseSplitMethod(cfg.split_method);
    extractor_.setConfig(c);
  } catch (const std::exception& e) {
    ROS_ERROR("line_extractor: reconfigure refused, every setting stays as it was: %s", e.what());
    showLineConfig(extractor_.config(), &cfg);  // the reply shows what holds
  }
}

void LineExtractorNode::onScan(const ros::MessageEvent<const sensor_msgs::LaserScan>& event) {
  const boost::shared_ptr<const sensor_msgs::LaserScan> msg = event.getConstMessage();
  laser::LaserScan2D scan = ros_conv::fromLaserScan(*msg);
  if (const std::string problem = laser::scanGeometryProblem(scan); !problem.empty()) {
    ROS_ERROR_THROTTLE(10.0, "line_extractor: scan dropped: %s", problem.c_str());
    ++bad_scans_;
    return;
  }
  std::vector<laser::LineSegment> segs;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    // An older scan is not passed on (the mapper would take it for a looped bag).
    if (stamp_order_.check(msg->header.stamp, event.getPublisherName()) ==
        ros_conv::StampOrder::Verdict::kDrop)
      return;
    bool found_now = false;
    no_returns_marked_ += no_return_.mark(&scan.ranges_m, scan.range_max_m, &found_now);
    if (found_now)
      ROS_WARN("line_extractor: the scans' range_max is %.2f m, but %ld readings are exactly "
               "%.2f m and none spread below: taken for the laser's no-return value (not walls)",
               scan.range_max_m, no_return_.readingsAtValue(), *no_return_.value());
    segs = extractor_.extract(scan);
  }
  const LineSegmentArray lines = ros_conv::toLineSegmentArray(segs, msg->header);
  lines_pub_.publish(lines);
  if (markers_pub_.getNumSubscribers() > 0)
    markers_pub_.publish(lineMarkers(lines, "lines", 1.0f, 0.3f, 0.0f));
  ++scans_;
  diagnostics_.tick();
  diagnostics_.update();
}

// The node's main (src/nodes, ros/node_main.h) links this one instance.
template int runNode<LineExtractorNode>(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
