#pragma once
// The image intake every camera node shares: keeps the images in stamp order (ros_conv::StampOrder:
// an older image is dropped, time really going back restarts), drops images that come faster than
// a rate on their stamps (max_rate_hz <= 0: none), and converts the rest to bgr8 or to YUV (the
// colour nodes), reporting an unreadable image with a throttled error naming the node and the
// problem.
#include <sensor_msgs/Image.h>

#include <opencv2/core.hpp>
#include <string>

#include "adaptive_perception/ros/stamp_order.h"

namespace adaptive_perception::ros_conv {

class ImageGate {
 public:
  enum class Output { kBgr8, kYuv };
  ImageGate(std::string node, double max_rate_hz, ros_conv::StampOrderConfig order = {},
            Output output = Output::kBgr8)
      : node_(node),
        max_rate_hz_(max_rate_hz),
        output_(output),
        order_(std::move(node), "image", order) {}

  enum class Result { kProcess, kTooSoon, kOutOfOrder, kBadImage };
  /// kProcess with *image filled (bgr8 or YUV, CV_8UC3), or why not (image_transport does not
  /// say who published an image, so the warnings cannot name it). *time_went_back is set when time really went back (StampOrder's
  /// kRestart: the caller restarts its filter; the image is still judged); an image only a little
  /// older than the last is kOutOfOrder.
  Result accept(const sensor_msgs::Image& msg, cv::Mat* image, bool* time_went_back);
  /// accept() for a node whose filter restarts by itself when time goes back: true to process the
  /// image (*image filled); false for an image too soon, out of order or bad (counted here).
  bool admit(const sensor_msgs::Image& msg, cv::Mat* image) {
    bool went_back = false;
    return accept(msg, image, &went_back) == Result::kProcess;
  }
  long badImages() const { return bad_images_; }
  long outOfOrder() const { return order_.dropped(); }

 private:
  std::string node_;
  double max_rate_hz_;
  Output output_;
  StampOrder order_;
  ros::Time last_processed_;
  long bad_images_ = 0;
};

}  // namespace adaptive_perception::ros_conv
