#include "adaptive_perception/ros/parameter_docs.h"

#include <stdexcept>

#include "adaptive_perception/ros/appearance_localizer_node.h"
#include "adaptive_perception/ros/camera_preview_node.h"
#include "adaptive_perception/ros/color_estimator_node.h"
#include "adaptive_perception/ros/condensation_tracker_node.h"
#include "adaptive_perception/ros/ekf_slam_mapper_node.h"
#include "adaptive_perception/ros/field_map_publisher_node.h"
#include "adaptive_perception/ros/ground_truth_tf_publisher_node.h"
#include "adaptive_perception/ros/head_tf_publisher_node.h"
#include "adaptive_perception/ros/histogram_place_recognizer_node.h"
#include "adaptive_perception/ros/line_extractor_node.h"
#include "adaptive_perception/ros/rbpf_localizer_node.h"

namespace adaptive_perception::ros_params {

const std::map<std::string, std::vector<config::ParameterDoc>>& nodeParameters() {
  static const std::map<std::string, std::vector<config::ParameterDoc>> nodes = {
      {"appearance_localizer", AppearanceLocalizerNode::parameters()},
      {"camera_preview", CameraPreviewNode::parameters()},
      {"color_estimator", ColorEstimatorNode::parameters()},
      {"condensation_tracker", CondensationTrackerNode::parameters()},
      {"ekf_slam_mapper", EkfSlamMapperNode::parameters()},
      {"field_map_publisher", FieldMapPublisherNode::parameters()},
      {"ground_truth_tf_publisher", GroundTruthTfNode::parameters()},
      {"head_tf_publisher", HeadTfNode::parameters()},
      {"histogram_place_recognizer", HistogramPlaceRecognizerNode::parameters()},
      {"line_extractor", LineExtractorNode::parameters()},
      {"rbpf_localizer", RbpfLocalizerNode::parameters()}};
  return nodes;
}

std::vector<config::ParameterDoc> joinRows(
    std::initializer_list<std::vector<config::ParameterDoc>> parts) {
  std::vector<config::ParameterDoc> rows;
  for (const auto& part : parts) rows.insert(rows.end(), part.begin(), part.end());
  return rows;
}

std::string parameterBlockBegin(const std::string& node) {
  return "<!-- parameters: made by `describe_parameters --node " + node +
         " --update`; do not edit by hand -->\n";
}

std::string parameterBlockEnd() { return "<!-- parameters: end -->\n"; }

std::string parameterBlock(const std::string& node) {
  const auto it = nodeParameters().find(node);
  if (it == nodeParameters().end()) throw std::runtime_error("no parameter table for node " + node);
  return parameterBlockBegin(node) + config::markdownTable(it->second) + parameterBlockEnd();
}

std::string withParameterBlock(const std::string& page, const std::string& node) {
  const std::string begin = parameterBlockBegin(node), end = parameterBlockEnd();
  const size_t b = page.find(begin);
  const size_t e = b == std::string::npos ? b : page.find(end, b);
  if (e == std::string::npos)
    throw std::runtime_error("the page has no parameter block for " + node + " (add the lines '" +
                             begin.substr(0, begin.size() - 1) + "' and '" +
                             end.substr(0, end.size() - 1) + "')");
  return page.substr(0, b) + parameterBlock(node) + page.substr(e + end.size());
}

}  // namespace adaptive_perception::ros_params
