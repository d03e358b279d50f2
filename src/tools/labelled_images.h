#pragma once
// Labelled images for the place tools (train_places, evaluate_places, bench_places): from a bag
// (camera/image_raw, labelled by the ground_truth/place message of the same stamp, or the latest
// one before it; with the ground_truth/pose of that stamp when the bag has one) or from a CSV image
// list (io/image_list.h). Images that cannot be read are
// reported on stderr and skipped; images labelled "none" (outside every place) are skipped unless
// asked for.
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/String.h>

#include <array>
#include <functional>
#include <iostream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>

#include "adaptive_perception/io/image_list.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/topics.h"

namespace adaptive_perception::tools {

struct LabelledImage {
  cv::Mat bgr;
  std::string label;
  std::string source;  // "file.bag@12.500" or the image path
  double stamp_s = 0.0;
  std::optional<std::array<double, 3>> pose;  // bags: ground_truth/pose at the image (x, y, yaw)
  std::optional<std::array<double, 3>> odom;  // bags: odom (odom -> base_link) at the image
};

/// Calls `fn` for each labelled image in order; returns the number delivered. Throws
/// std::runtime_error when the bag or list cannot be opened (or, without `keep_unplaced`, the bag
/// has no ground_truth/place). `keep_unplaced`: every image is delivered, those outside every
/// place (or before the first place message) labelled "none" (a reference drive keeps them all).
inline long forEachLabelledImage(const std::string& bag_path, const std::string& list_path,
                                 const std::function<void(const LabelledImage&)>& fn,
                                 bool keep_unplaced = false) {
  long delivered = 0, skipped = 0;
  if (!list_path.empty()) {
    for (const io::LabelledPath& p : io::readImageList(list_path)) {
      LabelledImage li;
      li.bgr = cv::imread(p.path, cv::IMREAD_COLOR);
      if (li.bgr.empty()) {
        std::cerr << list_path << ":" << p.line << ": cannot read image '" << p.path
                  << "', skipped\n";
        ++skipped;
        continue;
      }
      if (p.label == "none" && !keep_unplaced) continue;
      li.label = p.label;
      li.source = p.path;
      li.stamp_s = static_cast<double>(delivered);
      fn(li);
      ++delivered;
    }
    return delivered;
  }
  rosbag::Bag bag;
  try {
    bag.open(bag_path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error(bag_path + ": cannot open bag: " + e.what());
  }
  const std::string image_topic = std::string("/") + ros_topics::kCameraImage;
  const std::string place_topic = std::string("/") + ros_topics::kGroundTruthPlace;
  std::map<double, std::string> places;
  {
    rosbag::View v(bag, rosbag::TopicQuery(std::vector<std::string>{place_topic}));
    for (const rosbag::MessageInstance& m : v)
      if (const auto s = m.instantiate<std_msgs::String>()) places[m.getTime().toSec()] = s->data;
  }
  if (places.empty() && !keep_unplaced)
    throw std::runtime_error(bag_path + ": no " + place_topic +
                             " messages: cannot label the images (use --list for image lists)");
  std::map<double, std::array<double, 3>> poses;
  {
    const std::string pose_topic = std::string("/") + ros_topics::kGroundTruthPose;
    rosbag::View pv(bag, rosbag::TopicQuery(std::vector<std::string>{pose_topic}));
    for (const rosbag::MessageInstance& m : pv)
      if (const auto p = m.instantiate<geometry_msgs::PoseStamped>()) {
        const math::SE2 se2 = ros_conv::toSE2(p->pose);
        poses[p->header.stamp.toSec()] = {se2.x_m, se2.y_m, se2.yaw_rad};
      }
  }
  std::map<double, std::array<double, 3>> odoms;
  {
    const std::string odom_topic = std::string("/") + ros_topics::kOdom;
    rosbag::View ov(bag, rosbag::TopicQuery(std::vector<std::string>{odom_topic}));
    for (const rosbag::MessageInstance& m : ov)
      if (const auto o = m.instantiate<nav_msgs::Odometry>()) {
        const math::SE2 se2 = ros_conv::toSE2(o->pose.pose);
        odoms[o->header.stamp.toSec()] = {se2.x_m, se2.y_m, se2.yaw_rad};
      }
  }
  rosbag::View v(bag, rosbag::TopicQuery(std::vector<std::string>{image_topic}));
  for (const rosbag::MessageInstance& m : v) {
    const auto img = m.instantiate<sensor_msgs::Image>();
    if (!img) continue;
    const double t = img->header.stamp.toSec();
    std::string label = "none";
    auto it = places.upper_bound(t + 1e-6);
    if (it != places.begin()) label = std::prev(it)->second;
    if (keep_unplaced && label.empty()) label = "none";
    if (label.empty() || (label == "none" && !keep_unplaced)) {
      if (it == places.begin() && !keep_unplaced) ++skipped;
      continue;
    }
    LabelledImage li;
    try {
      li.bgr = ros_conv::imageToBgr8(*img);
    } catch (const ros_conv::ImageFormatError& e) {
      std::cerr << bag_path << ": image at " << t << " s skipped: " << e.what() << "\n";
      ++skipped;
      continue;
    }
    li.label = label;
    char src[64];
    std::snprintf(src, sizeof(src), "@%.3f", t);
    li.source = bag_path + src;
    li.stamp_s = t;
    auto pit = poses.upper_bound(t + 1e-6);
    if (pit != poses.begin() && t - std::prev(pit)->first < 0.1) li.pose = std::prev(pit)->second;
    auto oit = odoms.upper_bound(t + 1e-6);
    if (oit != odoms.begin() && t - std::prev(oit)->first < 0.1) li.odom = std::prev(oit)->second;
    fn(li);
    ++delivered;
  }
  if (skipped > 0) std::cerr << bag_path << ": " << skipped << " images skipped\n";
  return delivered;
}

}  // namespace adaptive_perception::tools
