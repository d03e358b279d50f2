#include "adaptive_perception/ros/compressed_transport.h"

#include <ros/console.h>
#include <ros/names.h>
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

sensor_msgs::ImagePtr decompressImage(const sensor_msgs::CompressedImage& compressed,
                                      std::int64_t max_pixels) {
  const bool grey = compressed.format.find("compressed mono8") != std::string::npos ||
                    compressed.format.rfind("mono8", 0) == 0;
  cv::Mat pixels;
  try {
    pixels = io::decodeImage(compressed.data, grey, max_pixels);
  } catch (const ImageFormatError& e) {
    throw ImageFormatError("'" + compressed.format + "': " + e.what());
  }
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
