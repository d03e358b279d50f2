#include "adaptive_perception/ros/bag_frames.h"

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2/buffer_core.h>
#include <tf2/exceptions.h>
#include <tf2_msgs/TFMessage.h>

#include <cstring>
#include <stdexcept>

#include "adaptive_perception/LightingState.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/topics.h"

namespace adaptive_perception::ros_bag {

namespace T = adaptive_perception::ros_topics;

namespace {
bool isTopic(const rosbag::MessageInstance& m, const char* topic) {
  const std::string& t = m.getTopic();
  return t == topic || (t.size() == std::strlen(topic) + 1 && t[0] == '/' &&
                        t.compare(1, std::string::npos, topic) == 0);
}
}  // namespace

BagFrameReader::~BagFrameReader() = default;

BagFrameReader::BagFrameReader(const std::string& path, const std::string& camera_frame)
    : path_(path), camera_frame_(camera_frame), camera_(world::PinholeCamera::aiboErs7()) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot read bag: " + e.what());
  }
  rosbag::View all(bag);
  const double span = (all.getEndTime() - all.getBeginTime()).toSec();
  tf_ = std::make_unique<tf2::BufferCore>(ros::Duration(span + 10.0));
  std::map<ros::Time, Eigen::Isometry3d> truth, odom;
  bool has_images = false;
  for (const rosbag::MessageInstance& m : all) {
    if (isTopic(m, "tf") || isTopic(m, "tf_static")) {
      const bool is_static = isTopic(m, "tf_static");
      if (auto tf = m.instantiate<tf2_msgs::TFMessage>())
        for (const auto& t : tf->transforms) tf_->setTransform(t, "bag", is_static);
    } else if (isTopic(m, T::kGroundTruthPose)) {
      if (auto p = m.instantiate<geometry_msgs::PoseStamped>())
        truth[p->header.stamp] = ros_conv::toIsometry(p->pose);
    } else if (isTopic(m, T::kOdom)) {
      if (auto o = m.instantiate<nav_msgs::Odometry>())
        odom[o->header.stamp] = ros_conv::toIsometry(o->pose.pose);
    } else if (isTopic(m, T::kCameraLabels)) {
      if (auto l = m.instantiate<sensor_msgs::Image>()) {
        try {
          labels_[l->header.stamp] = ros_conv::imageToMono8(*l);
        } catch (const std::exception&) {
        }
      }
    } else if (isTopic(m, T::kCameraInfo) && !has_camera_info_) {
      if (auto ci = m.instantiate<sensor_msgs::CameraInfo>()) {
        if (ros_conv::hasDistortion(*ci))
          throw std::runtime_error(path + ": camera_info has lens distortion; the evaluation "
                                          "tools take undistorted images (the nodes rectify)");
        camera_ = ros_conv::fromCameraInfo(*ci);
        has_camera_info_ = true;
      }
    } else if (isTopic(m, T::kLightingState)) {
      if (auto ls = m.instantiate<adaptive_perception::LightingState>())
        conditions_[ls->header.stamp] = ls->condition;
    } else if (isTopic(m, T::kCameraImage)) {
      has_images = true;
    }
  }
  if (!has_images) throw std::runtime_error(path + ": no camera/image_raw messages");
  // Close the tree to `map` with the ground truth.
  for (const auto& [stamp, map_base] : truth) {
    auto it = odom.find(stamp);
    if (it == odom.end()) continue;
    tf_->setTransform(
        ros_conv::toTransform(map_base * it->second.inverse(), T::kMapFrame, T::kOdomFrame, stamp),
        "ground_truth", false);
  }
}

std::vector<CameraFrame> BagFrameReader::readAll() {
  rosbag::Bag bag(path_, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{
                             T::kCameraImage, std::string("/") + T::kCameraImage}));
  std::vector<CameraFrame> frames;
  for (const rosbag::MessageInstance& m : view) {
    auto img = m.instantiate<sensor_msgs::Image>();
    if (!img) continue;
    CameraFrame f;
    f.stamp = img->header.stamp;
    f.camera = camera_;
    try {
      f.yuv = ros_conv::imageToYuv(*img);
    } catch (const std::exception&) {
      ++skipped_;
      continue;
    }
    if (auto it = labels_.find(f.stamp); it != labels_.end()) f.true_labels = it->second;
    if (auto it = conditions_.find(f.stamp); it != conditions_.end())
      f.lighting_condition = it->second;
    const std::string cam_frame =
        img->header.frame_id.empty() ? camera_frame_ : img->header.frame_id;
    try {
      const auto t = tf_->lookupTransform(T::kMapFrame, cam_frame, f.stamp);
      f.map_to_optical = ros_conv::toIsometry(t.transform);
      f.has_pose = true;
      f.map_to_base = ros_conv::toIsometry(
          tf_->lookupTransform(T::kMapFrame, T::kBaseFrame, f.stamp).transform);
      f.has_truth = true;
    } catch (const tf2::TransformException&) {
    }
    try {
      f.odom_to_base = ros_conv::toIsometry(
          tf_->lookupTransform(T::kOdomFrame, T::kBaseFrame, f.stamp).transform);
      f.base_to_optical =
          ros_conv::toIsometry(tf_->lookupTransform(T::kBaseFrame, cam_frame, f.stamp).transform);
      f.has_odom = true;
    } catch (const tf2::TransformException&) {
    }
    frames.push_back(std::move(f));
  }
  return frames;
}

}  // namespace adaptive_perception::ros_bag
