#pragma once
// The image intake every camera node shares: keeps the images in stamp order (ros_conv::StampOrder:
// an older image is dropped, time really going back restarts), drops images that come faster than
// a rate on their stamps (max_rate_hz <= 0: none), and converts the rest to bgr8 or to YUV (the
// colour nodes), reporting an unreadable image (a bad encoding or buffer, more pixels than the
// node's limit, or any exception while converting it) with a throttled error naming the node and
// the problem: no exception leaves accept().
#include <ros/console.h>
#include <sensor_msgs/Image.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/stamp_order.h"

namespace adaptive_perception::ros_conv {

/// An image node's intake settings (ros_params::loadImageIntake reads them).
struct ImageIntakeConfig {
  StampOrderConfig order;
  /// Images with more pixels (width x height) are refused before any copy is made.
  std::int64_t max_pixels = kDefaultMaxImagePixels;
};

class ImageGate {
 public:
  enum class Output { kBgr8, kYuv };
  ImageGate(std::string node, double max_rate_hz, ImageIntakeConfig intake = {},
            Output output = Output::kBgr8)
      : node_(node),
        max_rate_hz_(max_rate_hz),
        max_pixels_(intake.max_pixels),
        output_(output),
        order_(std::move(node), "image", intake.order) {}

  enum class Result { kProcess, kTooSoon, kOutOfOrder, kBadImage };
  /// kProcess with *image filled (bgr8 or YUV, CV_8UC3), or why not (image_transport does not
  /// say who published an image, so the warnings cannot name it). *time_went_back is set when time
  /// really went back (StampOrder's kRestart: the caller restarts its filter; the image is still
  /// judged); an image only a little older than the last is kOutOfOrder.
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
  std::int64_t max_pixels_;
  Output output_;
  StampOrder order_;
  ros::Time last_processed_;
  long bad_images_ = 0;
};

/// Runs `process` on an image a callback received; an exception it throws is logged (throttled,
/// naming the node and the image's stamp) instead of leaving the callback, where it would end the
/// node.
template <class F>
void processGuarded(const char* node, const sensor_msgs::Image& msg, F&& process) {
  try {
    process();
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(10.0, "%s: image at %.3f s not processed: %s", node,
                       msg.header.stamp.toSec(), e.what());
  }
}

}  // namespace adaptive_perception::ros_conv
