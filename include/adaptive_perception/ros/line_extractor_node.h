#pragma once
// line_extractor: wall segments from laser scans (split-and-merge, perception paper section 2.1).
//
// Its interface (parameters, subscribed and published topics, services, tf) is documented once,
// in docs/nodes/line_extractor.md; the parameter table there is made from parameters().
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <visualization_msgs/MarkerArray.h>

#include <memory>
#include <mutex>
#include <string>

#include "adaptive_perception/LineExtractorConfig.h"
#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/laser/line_extraction.h"
#include "adaptive_perception/laser/no_return.h"
#include "adaptive_perception/ros/stamp_order.h"
#include "adaptive_perception/ros/node_diagnostics.h"

namespace adaptive_perception {

/// rviz markers: one LINE_LIST of all segments plus their normals' feet (`ns` names the namespace).
visualization_msgs::MarkerArray lineMarkers(const LineSegmentArray& lines, const std::string& ns,
                                            float r, float g, float b);

class LineExtractorNode {
 public:
  LineExtractorNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Every private parameter the node reads (its doc page's table).
  static std::vector<config::ParameterDoc> parameters();

 private:
  void onScan(const ros::MessageEvent<const sensor_msgs::LaserScan>& event);
  void onReconfigure(adaptive_perception::LineExtractorConfig& c, uint32_t level);
  std::mutex mutex_;
  laser::LineExtractor extractor_;
  ros::Subscriber scan_sub_;
  ros::Publisher lines_pub_, markers_pub_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<adaptive_perception::LineExtractorConfig>>
      reconfigure_;
  ros_conv::StampOrder stamp_order_{"line_extractor", "scan"};
  long scans_ = 0, bad_scans_ = 0;
  // The laser's no-return value found from its readings, for a scan whose range_max is wrong
  // (laser/no_return.h); readings at it are not walls.
  laser::NoReturnFinder no_return_;
  long no_returns_marked_ = 0;
  ros_conv::NodeDiagnostics diagnostics_;  // last: its heartbeat stops before the state it reads goes
};

}  // namespace adaptive_perception
