#include "adaptive_perception/ros/compressed_transport.h"

#include <ros/console.h>
#include <ros/names.h>
#include <sensor_msgs/image_encodings.h>

#include <algorithm>
#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <vector>

#include "adaptive_perception/ros/msg_conversion.h"

namespace adaptive_perception::ros_conv {

namespace enc = sensor_msgs::image_encodings;

sensor_msgs::CompressedImage compressImage(const sensor_msgs::Image& image,
                                           const CompressionConfig& config) {
  if (config.format != "jpeg" && config.format != "png")
    throw ImageFormatError("compressed format '" + config.format + "' (allowed: jpeg, png)");
  if (config.jpeg_quality < 1 || config.jpeg_quality > 100)
    throw ImageFormatError("jpeg_quality = " + std::to_string(config.jpeg_quality) +
                           " (allowed: 1..100)");
  if (config.png_level < 0 || config.png_level > 9)
    throw ImageFormatError("png_level = " + std::to_string(config.png_level) + " (allowed: 0..9)");
  const bool grey = image.encoding == enc::MONO8;
  const cv::Mat pixels = grey ? imageToMono8(image) : imageToBgr8(image);
  const bool jpeg = config.format == "jpeg";
  const std::vector<int> params =
      jpeg ? std::vector<int>{cv::IMWRITE_JPEG_QUALITY, config.jpeg_quality}
           : std::vector<int>{cv::IMWRITE_PNG_COMPRESSION, config.png_level};
  sensor_msgs::CompressedImage out;
  out.header = image.header;
  out.format = image.encoding + "; " + config.format + " compressed " + (grey ? "mono8" : "bgr8");
  if (!cv::imencode(jpeg ? ".jpg" : ".png", pixels, out.data, params))
    throw ImageFormatError("the " + config.format + " encoder refused a " +
                           std::to_string(pixels.cols) + "x" + std::to_string(pixels.rows) +
                           " image");
  return out;
}

namespace {
std::uint32_t bigEndian(const std::vector<std::uint8_t>& d, std::size_t at, int bytes) {
  std::uint32_t v = 0;
  for (int k = 0; k < bytes; ++k) v = (v << 8) | d[at + static_cast<std::size_t>(k)];
  return v;
}
}  // namespace

std::optional<cv::Size> encodedImageSize(const std::vector<std::uint8_t>& d) {
  // PNG: the 8-byte signature, then the IHDR chunk (length, "IHDR", width, height).
  static const std::uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (d.size() >= 24 && std::equal(kPng, kPng + 8, d.begin())) {
    if (std::memcmp(d.data() + 12, "IHDR", 4) != 0) return std::nullopt;
    const std::uint32_t w = bigEndian(d, 16, 4), h = bigEndian(d, 20, 4);
    if (w == 0 || h == 0 || w > 0x7fffffffu || h > 0x7fffffffu) return std::nullopt;
    return cv::Size(static_cast<int>(w), static_cast<int>(h));
  }
  // JPEG: SOI, then marker segments up to the first start of frame (SOF0-15 but DHT C4, JPG C8
  // and DAC CC), which holds precision, height, width.
  if (d.size() < 4 || d[0] != 0xff || d[1] != 0xd8) return std::nullopt;
  std::size_t at = 2;
  while (at + 4 <= d.size()) {
    if (d[at] != 0xff) return std::nullopt;
    const std::uint8_t marker = d[at + 1];
    if (marker == 0xff) {  // fill byte
      ++at;
      continue;
    }
    if (marker == 0x01 || (marker >= 0xd0 && marker <= 0xd7)) {  // no length
      at += 2;
      continue;
    }
    // Not a marker (FF 00 is a stuffed byte, 02-BF are reserved): a decoder reads on byte by
    // byte there, so a size read past it could be another than the one decoded.
    if (marker == 0x00 || (marker >= 0x02 && marker < 0xc0)) return std::nullopt;
    if (marker == 0xd9 || marker == 0xda) return std::nullopt;  // end, or scan before a frame
    const std::size_t length = bigEndian(d, at + 2, 2);
    if (length < 2) return std::nullopt;
    const bool sof =
        marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc;
    if (sof) {
      if (length < 7 || at + 9 > d.size()) return std::nullopt;
      const std::uint32_t h = bigEndian(d, at + 5, 2), w = bigEndian(d, at + 7, 2);
      if (w == 0 || h == 0) return std::nullopt;  // a height given later (DNL) is not taken
      return cv::Size(static_cast<int>(w), static_cast<int>(h));
    }
    at += 2 + length;
  }
  return std::nullopt;
}

sensor_msgs::ImagePtr decompressImage(const sensor_msgs::CompressedImage& compressed,
                                      std::int64_t max_pixels) {
  const bool grey = compressed.format.find("compressed mono8") != std::string::npos ||
                    compressed.format.rfind("mono8", 0) == 0;
  const std::optional<cv::Size> size = encodedImageSize(compressed.data);
  if (!size)
    throw ImageFormatError("compressed image ('" + compressed.format + "', " +
                           std::to_string(compressed.data.size()) +
                           " bytes) is not a JPEG or PNG file whose header gives its size");
  const std::int64_t pixels = static_cast<std::int64_t>(size->width) * size->height;
  if (pixels > max_pixels)
    throw ImageFormatError("compressed image of " + std::to_string(size->width) + "x" +
                           std::to_string(size->height) + " (" + std::to_string(pixels) +
                           " pixels) not decoded: more than the limit of " +
                           std::to_string(max_pixels));
  cv::Mat pixels_mat;
  try {
    pixels_mat = cv::imdecode(compressed.data, grey ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
  } catch (const std::exception& e) {  // cv::Exception, bad_alloc
    throw ImageFormatError("compressed image not decoded: " + std::string(e.what()));
  }
  if (pixels_mat.empty())
    throw ImageFormatError("compressed image ('" + compressed.format + "', " +
                           std::to_string(compressed.data.size()) + " bytes) could not be decoded");
  return boost::make_shared<sensor_msgs::Image>(grey ? mono8ToImage(pixels_mat, compressed.header)
                                                     : bgr8ToImage(pixels_mat, compressed.header));
}

void CompressedPublisher::publish(const sensor_msgs::Image& image,
                                  const PublishFn& publish_fn) const {
  CompressionConfig config;
  nh().param<std::string>("format", config.format, config.format);
  nh().param("jpeg_quality", config.jpeg_quality, config.jpeg_quality);
  nh().param("png_level", config.png_level, config.png_level);
  try {
    publish_fn(compressImage(image, config));
  } catch (const std::exception& e) {  // ImageFormatError, and cv::Exception or bad_alloc
    ROS_ERROR_THROTTLE(10.0, "%s: image not compressed: %s", getTopic().c_str(), e.what());
  }
}

void CompressedSubscriber::internalCallback(const sensor_msgs::CompressedImageConstPtr& message,
                                            const Callback& user_cb) {
  // The limit of the node that subscribes: its ~max_image_pixels (this plugin's parameters are
  // in <node>/compressed).
  int max_pixels = static_cast<int>(kDefaultMaxImagePixels);
  ros::NodeHandle(ros::names::parentNamespace(nh().getNamespace()))
      .getParamCached("max_image_pixels", max_pixels);
  sensor_msgs::ImagePtr image;
  try {
    image = decompressImage(*message, max_pixels);
  } catch (const std::exception& e) {  // ImageFormatError, and bad_alloc
    ROS_ERROR_THROTTLE(10.0, "%s: image dropped: %s", getTopic().c_str(), e.what());
    return;
  }
  user_cb(image);
}

}  // namespace adaptive_perception::ros_conv

PLUGINLIB_EXPORT_CLASS(adaptive_perception::ros_conv::CompressedPublisher,
                       image_transport::PublisherPlugin)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::ros_conv::CompressedSubscriber,
                       image_transport::SubscriberPlugin)
