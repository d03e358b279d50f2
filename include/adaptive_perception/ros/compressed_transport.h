#pragma once
// The "compressed" image_transport (camera/image_raw/compressed, sensor_msgs/CompressedImage),
// which Debian's ROS does not package: JPEG or PNG, in the message format of ROS's
// compressed_image_transport (format "<encoding>; jpeg compressed bgr8", data the encoded file),
// so that its bags and cameras work here and ours there. Images in bgr8, rgb8 and yuv422 are sent
// as colour (bgr8), mono8 as grey; a subscriber gets bgr8, or mono8 for grey. Loaded by
// image_transport as plugins (image_transport_plugins.xml); where ROS's own plugin is also
// installed, pluginlib uses one of the two.
//
// Publisher parameters, in <topic>/compressed/ as ROS's plugin names them: format (jpeg | png,
// default jpeg), jpeg_quality (1..100, default 80), png_level (0..9, default 9), as ROS's.
// The subscriber refuses, before decoding, an image of more pixels than the subscribing node's
// ~max_image_pixels (ros_conv::kDefaultMaxImagePixels when unset).
#include <image_transport/simple_publisher_plugin.h>
#include <image_transport/simple_subscriber_plugin.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "adaptive_perception/ros/msg_conversion.h"

namespace adaptive_perception::ros_conv {

struct CompressionConfig {
  std::string format = "jpeg";  // jpeg | png
  int jpeg_quality = 80;        // 1..100 (ROS's plugin's default)
  int png_level = 9;            // 0..9 (zlib; ROS's plugin's default)
};

/// The image compressed; throws ImageFormatError for an encoding imageToBgr8 cannot read, or a bad
/// config (naming the field).
sensor_msgs::CompressedImage compressImage(const sensor_msgs::Image& image,
                                           const CompressionConfig& config);
/// The image a CompressedImage holds (bgr8, or mono8 for a grey one), with its header
/// (io::decodeImage: its size read from the file's header before decoding); throws
/// ImageFormatError naming the message's format and what was wrong.
sensor_msgs::ImagePtr decompressImage(const sensor_msgs::CompressedImage& compressed,
                                      std::int64_t max_pixels = kDefaultMaxImagePixels);

class CompressedPublisher
    : public image_transport::SimplePublisherPlugin<sensor_msgs::CompressedImage> {
 public:
  std::string getTransportName() const override { return "compressed"; }

 protected:
  void publish(const sensor_msgs::Image& image, const PublishFn& publish_fn) const override;
};

class CompressedSubscriber
    : public image_transport::SimpleSubscriberPlugin<sensor_msgs::CompressedImage> {
 public:
  std::string getTransportName() const override { return "compressed"; }

 protected:
  void internalCallback(const sensor_msgs::CompressedImageConstPtr& message,
                        const Callback& user_cb) override;
};

}  // namespace adaptive_perception::ros_conv
