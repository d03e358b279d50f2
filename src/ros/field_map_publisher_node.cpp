#include "adaptive_perception/ros/field_map_publisher_node.h"

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/ros/node_run.h"

namespace adaptive_perception {

namespace {
std_msgs::ColorRGBA displayColor(std::uint8_t cls, float alpha = 1.0f) {
  const auto bgr = world::colorClassDisplayBgr(cls);
  std_msgs::ColorRGBA c;
  c.r = bgr[2] / 255.0f;
  c.g = bgr[1] / 255.0f;
  c.b = bgr[0] / 255.0f;
  c.a = alpha;
  return c;
}
}  // namespace

visualization_msgs::MarkerArray fieldMapMarkers(const world::FieldMap& map,
                                                const std::string& frame_id,
                                                const ros::Time& stamp) {
  visualization_msgs::MarkerArray out;
  int id = 0;
  auto base = [&](const std::string& ns, int type) {
    visualization_msgs::Marker m;
    m.header.frame_id = frame_id;
    m.header.stamp = stamp;
    m.ns = ns;
    m.id = id++;
    m.type = type;
    m.action = visualization_msgs::Marker::ADD;
    m.pose.orientation.w = 1.0;
    return m;
  };
  {  // carpet, slightly below z = 0 so that lines show on top
    auto m = base("carpet", visualization_msgs::Marker::CUBE);
    m.pose.position.z = -0.006;
    m.scale.x = 2 * map.carpetHalfLength();
    m.scale.y = 2 * map.carpetHalfWidth();
    m.scale.z = 0.01;
    m.color = displayColor(world::kGreen);
    out.markers.push_back(m);
  }
  for (const auto& r : map.groundRects()) {
    auto m = base("lines", visualization_msgs::Marker::CUBE);
    m.pose.position.x = 0.5 * (r.x0_m + r.x1_m);
    m.pose.position.y = 0.5 * (r.y0_m + r.y1_m);
    m.pose.position.z = 0.0005;
    m.scale.x = r.x1_m - r.x0_m;
    m.scale.y = r.y1_m - r.y0_m;
    m.scale.z = 0.001;
    m.color = displayColor(r.color);
    out.markers.push_back(m);
  }
  for (const auto& ring : map.groundRings()) {
    auto m = base("lines", visualization_msgs::Marker::LINE_STRIP);
    m.scale.x = ring.r_outer_m - ring.r_inner_m;
    m.color = displayColor(ring.color);
    const double r = 0.5 * (ring.r_inner_m + ring.r_outer_m);
    for (int k = 0; k <= 72; ++k) {
      geometry_msgs::Point p;
      p.x = ring.cx_m + r * std::cos(2 * math::kPi * k / 72);
      p.y = ring.cy_m + r * std::sin(2 * math::kPi * k / 72);
      p.z = 0.001;
      m.points.push_back(p);
    }
    out.markers.push_back(m);
  }
  for (const auto& q : map.quads()) {
    auto m = base(q.kind == world::SurfaceKind::kGoal ? "goals" : "walls",
                  visualization_msgs::Marker::CUBE);
    const Eigen::Vector2d mid = 0.5 * (q.p0_m + q.p1_m), d = q.p1_m - q.p0_m;
    m.pose.position.x = mid.x();
    m.pose.position.y = mid.y();
    m.pose.position.z = 0.5 * (q.z0_m + q.z1_m);
    const double yaw = std::atan2(d.y(), d.x());
    m.pose.orientation.z = std::sin(0.5 * yaw);
    m.pose.orientation.w = std::cos(0.5 * yaw);
    m.scale.x = d.norm();
    m.scale.y = 0.02;
    m.scale.z = q.z1_m - q.z0_m;
    m.color = displayColor(q.color, q.kind == world::SurfaceKind::kWall ? 0.6f : 1.0f);
    out.markers.push_back(m);
  }
  for (const auto& c : map.cylinders()) {
    for (const auto& band : c.bands) {
      auto m = base(c.kind == world::SurfaceKind::kGoal ? "goals" : "beacons",
                    visualization_msgs::Marker::CYLINDER);
      m.pose.position.x = c.cx_m;
      m.pose.position.y = c.cy_m;
      m.pose.position.z = 0.5 * (band.z0_m + band.z1_m);
      m.scale.x = m.scale.y = 2 * c.radius_m;
      m.scale.z = band.z1_m - band.z0_m;
      m.color = displayColor(band.color);
      out.markers.push_back(m);
    }
  }
  for (const auto& s : map.spheres()) {
    auto m = base("ball", visualization_msgs::Marker::SPHERE);
    m.pose.position.x = s.centre_m.x();
    m.pose.position.y = s.centre_m.y();
    m.pose.position.z = s.centre_m.z();
    m.scale.x = m.scale.y = m.scale.z = 2 * s.radius_m;
    m.color = displayColor(s.color);
    out.markers.push_back(m);
  }
  return out;
}

std::vector<config::ParameterDoc> FieldMapPublisherNode::parameters() {
  return {ros_params::fieldFileParameter(),
          {"frame_id", "string", ros_topics::kMapFrame, "", "the frame of the markers"}};
}

FieldMapPublisherNode::FieldMapPublisherNode(ros::NodeHandle nh, ros::NodeHandle pnh) {
  std::string file;
  const world::FieldMap map = ros_params::loadFieldMap(pnh, &file);
  const std::string frame = ros_params::getFrameId(pnh, "frame_id", ros_topics::kMapFrame);
  pub_ = nh.advertise<visualization_msgs::MarkerArray>(ros_topics::kFieldMap, 1, /*latch=*/true);
  pub_.publish(fieldMapMarkers(map, frame, ros::Time(0)));
  ROS_INFO("field_map_publisher: published %s (%.2f x %.2f m field) in frame '%s'", file.c_str(),
           map.dimensions().field_length_m, map.dimensions().field_width_m, frame.c_str());
}

// The node's main (src/nodes, ros/node_main.h) links this one instance.
template int runNode<FieldMapPublisherNode>(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
