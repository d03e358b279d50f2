#include "adaptive_perception/ros/compressed_transport.h"

#include <ros/console.h>
#include <sensor_msgs/image_encodings.h>

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

sensor_msgs::ImagePtr decompressImage(const sensor_msgs::CompressedImage& compressed) {
  const bool grey = compressed.format.find("compressed mono8") != std::string::npos ||
                    compressed.format.rfind("mono8", 0) == 0;
  cv::Mat pixels;
  try {
    pixels = cv::imdecode(compressed.data, grey ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
  } catch (const cv::Exception& e) {
    throw ImageFormatError("compressed image not decoded: " + std::string(e.what()));
  }
  if (pixels.empty())
    throw ImageFormatError("compressed image ('" + compressed.format + "', " +
                           std::to_string(compressed.data.size()) +
                           " bytes) is not a JPEG or PNG file");
  return boost::make_shared<sensor_msgs::Image>(grey ? mono8ToImage(pixels, compressed.header)
                                                     : bgr8ToImage(pixels, compressed.header));
}

void CompressedPublisher::publish(const sensor_msgs::Image& image,
                                  const PublishFn& publish_fn) const {
  CompressionConfig config;
  nh().param<std::string>("format", config.format, config.format);
  nh().param("jpeg_quality", config.jpeg_quality, config.jpeg_quality);
  nh().param("png_level", config.png_level, config.png_level);
  try {
    publish_fn(compressImage(image, config));
  } catch (const ImageFormatError& e) {
    ROS_ERROR_THROTTLE(10.0, "%s: image not compressed: %s", getTopic().c_str(), e.what());
  }
}

void CompressedSubscriber::internalCallback(const sensor_msgs::CompressedImageConstPtr& message,
                                            const Callback& user_cb) {
  try {
    user_cb(decompressImage(*message));
  } catch (const ImageFormatError& e) {
    ROS_ERROR_THROTTLE(10.0, "%s: image dropped: %s", getTopic().c_str(), e.what());
  }
}

}  // namespace adaptive_perception::ros_conv

PLUGINLIB_EXPORT_CLASS(adaptive_perception::ros_conv::CompressedPublisher,
                       image_transport::PublisherPlugin)
PLUGINLIB_EXPORT_CLASS(adaptive_perception::ros_conv::CompressedSubscriber,
                       image_transport::SubscriberPlugin)
