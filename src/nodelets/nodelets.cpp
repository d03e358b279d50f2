// Every node as a nodelet (ros/node_nodelet.h), listed in nodelet_plugins.xml, e.g.
//   rosrun nodelet nodelet standalone adaptive_perception/color_estimator
//   rosrun nodelet nodelet load adaptive_perception/rbpf_localizer MANAGER
#include <pluginlib/class_list_macros.hpp>

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
#include "adaptive_perception/ros/node_nodelet.h"
#include "adaptive_perception/ros/rbpf_localizer_node.h"

namespace adaptive_perception {
using AppearanceLocalizerNodelet = NodeNodelet<AppearanceLocalizerNode>;
using CameraPreviewNodelet = NodeNodelet<CameraPreviewNode>;
using ColorEstimatorNodelet = NodeNodelet<ColorEstimatorNode>;
using CondensationTrackerNodelet = NodeNodelet<CondensationTrackerNode>;
using EkfSlamMapperNodelet = NodeNodelet<EkfSlamMapperNode>;
using FieldMapPublisherNodelet = NodeNodelet<FieldMapPublisherNode>;
using GroundTruthTfNodelet = NodeNodelet<GroundTruthTfNode>;
using HeadTfNodelet = NodeNodelet<HeadTfNode>;
using HistogramPlaceRecognizerNodelet = NodeNodelet<HistogramPlaceRecognizerNode>;
using LineExtractorNodelet = NodeNodelet<LineExtractorNode>;
using RbpfLocalizerNodelet = NodeNodelet<RbpfLocalizerNode>;
}  // namespace adaptive_perception

PLUGINLIB_EXPORT_CLASS(adaptive_perception::AppearanceLocalizerNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::CameraPreviewNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::ColorEstimatorNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::CondensationTrackerNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::EkfSlamMapperNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::FieldMapPublisherNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::GroundTruthTfNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::HeadTfNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::HistogramPlaceRecognizerNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::LineExtractorNodelet, nodelet::Nodelet)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::RbpfLocalizerNodelet, nodelet::Nodelet)
