#pragma once
// field_map_publisher: publishes the 3-D field map for rviz.
//
// Its interface (parameters, subscribed and published topics, services, tf) is documented once,
// in docs/nodes/field_map_publisher.md; the parameter table there is made from parameters().
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/world/field_map.h"

namespace adaptive_perception {

/// Markers showing `map` in `frame_id`; colours are the display colours of the classes.
visualization_msgs::MarkerArray fieldMapMarkers(const world::FieldMap& map,
                                                const std::string& frame_id,
                                                const ros::Time& stamp);

class FieldMapPublisherNode {
 public:
  /// Throws ros_params::ParamError or std::runtime_error (bad field file) with a clear message.
  FieldMapPublisherNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  /// Every private parameter the node reads (its doc page's table).
  static std::vector<config::ParameterDoc> parameters();

 private:
  ros::Publisher pub_;
};

}  // namespace adaptive_perception
