#include "adaptive_perception/ros/ground_truth_tf_publisher_node.h"

#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/ros/node_run.h"

namespace adaptive_perception {

namespace {
constexpr int kPathLength = 2000;
}  // namespace

std::vector<config::ParameterDoc> GroundTruthTfNode::parameters() {
  return {ros_params::frameParameter("map"),
          ros_params::frameParameter("odom"),
          ros_params::frameParameter("base"),
          {"path_length", "int", std::to_string(kPathLength), "[0, 100000]",
           "poses kept in ground_truth/path (0: no path)"},
          {"publish_tf", "bool", "true", "",
           "broadcast map -> odom; false when a localizer owns it (the path is still published)"}};
}

GroundTruthTfNode::GroundTruthTfNode(ros::NodeHandle nh, ros::NodeHandle pnh)
    : diagnostics_(nh, "ground_truth", 1.0, 1000.0) {
  map_frame_ = ros_params::getFrameId(pnh, "map_frame", ros_topics::kMapFrame);
  odom_frame_ = ros_params::getFrameId(pnh, "odom_frame", ros_topics::kOdomFrame);
  base_frame_ = ros_params::getFrameId(pnh, "base_frame", ros_topics::kBaseFrame);
  path_length_ = ros_params::getInRange(pnh, "path_length", kPathLength, 0, 100000);
  publish_tf_ = ros_params::get<bool>(pnh, "publish_tf", true);

  truth_sub_.subscribe(nh, ros_topics::kGroundTruthPose, 100);
  odom_sub_.subscribe(nh, ros_topics::kOdom, 100);
  sync_ =
      std::make_unique<message_filters::Synchronizer<Policy>>(Policy(50), truth_sub_, odom_sub_);
  sync_->registerCallback(&GroundTruthTfNode::callback, this);
  path_pub_ = nh.advertise<nav_msgs::Path>(ros_topics::kGroundTruthPath, 1);
  path_.header.frame_id = map_frame_;

}

void GroundTruthTfNode::callback(const geometry_msgs::PoseStampedConstPtr& truth,
                                 const nav_msgs::OdometryConstPtr& odom) {
  if (truth->header.frame_id != map_frame_) {
    ROS_WARN_THROTTLE(5.0, "ground_truth/pose is in frame '%s', expected '%s': skipped",
                      truth->header.frame_id.c_str(), map_frame_.c_str());
    return;
  }
  if (!last_stamp_.isZero() && truth->header.stamp < last_stamp_) {
    ROS_WARN("ground truth time jumped backwards (%.3f -> %.3f s): bag looped? Path cleared.",
             last_stamp_.toSec(), truth->header.stamp.toSec());
    path_.poses.clear();
  }
  last_stamp_ = truth->header.stamp;
  const Eigen::Isometry3d map_base = ros_conv::toIsometry(truth->pose);
  const Eigen::Isometry3d odom_base = ros_conv::toIsometry(odom->pose.pose);
  if (!map_base.matrix().allFinite() || !odom_base.matrix().allFinite()) {
    ROS_WARN_THROTTLE(5.0, "non-finite ground truth or odometry pose: skipped");
    return;
  }
  if (publish_tf_)
    broadcaster_.sendTransform(ros_conv::toTransform(map_base * odom_base.inverse(), map_frame_,
                                                     odom_frame_, truth->header.stamp));
  diagnostics_.tick();
  diagnostics_.update();
  if (path_length_ > 0) {
    path_.header.stamp = truth->header.stamp;
    path_.poses.push_back(*truth);
    if (static_cast<int>(path_.poses.size()) > path_length_) path_.poses.erase(path_.poses.begin());
    path_pub_.publish(path_);
  }
}

// The node's main (src/nodes, ros/node_main.h) links this one instance.
template int runNode<GroundTruthTfNode>(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
