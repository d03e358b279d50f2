#pragma once
// The image intake the camera nodes share: notices image time going backwards (a looped bag), drops
// images that come faster than a rate on their stamps, and converts the rest to bgr8, reporting an
// unreadable image with a throttled error naming the node and the problem.
#include <sensor_msgs/Image.h>

#include <opencv2/core.hpp>
#include <string>

namespace adaptive_perception::ros_conv {

class ImageGate {
 public:
  ImageGate(std::string node, double max_rate_hz)
      : node_(std::move(node)), max_rate_hz_(max_rate_hz) {}

  enum class Result { kProcess, kTooSoon, kBadImage };
  /// kProcess with *bgr filled, or why not. *time_went_back is set when this image is older than
  /// the previous one (the caller restarts its filter; the image is still judged).
  Result accept(const sensor_msgs::Image& msg, cv::Mat* bgr, bool* time_went_back);
  long badImages() const { return bad_images_; }

 private:
  std::string node_;
  double max_rate_hz_;
  ros::Time last_stamp_, last_processed_;
  long bad_images_ = 0;
};

}  // namespace adaptive_perception::ros_conv
