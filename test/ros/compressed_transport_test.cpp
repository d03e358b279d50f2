// The compressed image transport's encoding and decoding (ros/compressed_transport.h), without a
// master: PNG gives back every pixel, JPEG is close, grey stays grey, yuv422 arrives as the bgr8
// that imageToBgr8 makes of it, and what cannot be read is refused with a message naming why.
#include "adaptive_perception/ros/compressed_transport.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/ros/msg_conversion.h"

using namespace adaptive_perception;
using ros_conv::CompressionConfig;

namespace {

std_msgs::Header header() {
  std_msgs::Header h;
  h.stamp = ros::Time(12, 345);
  h.frame_id = "camera_optical_frame";
  return h;
}

// A smooth colour gradient with a few edges (JPEG's easy and hard cases).
cv::Mat testBgr() {
  cv::Mat bgr(60, 80, CV_8UC3);
  for (int r = 0; r < bgr.rows; ++r)
    for (int c = 0; c < bgr.cols; ++c)
      bgr.at<cv::Vec3b>(r, c) = cv::Vec3b(static_cast<uchar>(3 * c), static_cast<uchar>(4 * r),
                                          static_cast<uchar>(100 + c));
  cv::rectangle(bgr, cv::Rect(20, 15, 25, 20), cv::Scalar(20, 200, 240), cv::FILLED);
  return bgr;
}

double meanAbsDiff(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat d;
  cv::absdiff(a, b, d);
  const cv::Scalar m = cv::mean(d);
  return (m[0] + m[1] + m[2]) / a.channels();
}

}  // namespace

TEST(CompressedTransport, PngGivesBackEveryPixelAndTheHeader) {
  const sensor_msgs::Image in = ros_conv::bgr8ToImage(testBgr(), header());
  CompressionConfig c;
  c.format = "png";
  const sensor_msgs::CompressedImage z = ros_conv::compressImage(in, c);
  EXPECT_EQ(z.format, "bgr8; png compressed bgr8");
  EXPECT_EQ(z.header.stamp, in.header.stamp);
  const sensor_msgs::ImagePtr out = ros_conv::decompressImage(z);
  EXPECT_EQ(out->encoding, "bgr8");
  EXPECT_EQ(out->header.frame_id, "camera_optical_frame");
  EXPECT_EQ(meanAbsDiff(ros_conv::imageToBgr8(*out), testBgr()), 0.0);
}

TEST(CompressedTransport, JpegIsCloseAndSmallerThanRaw) {
  const sensor_msgs::Image in = ros_conv::bgr8ToImage(testBgr(), header());
  const sensor_msgs::CompressedImage z = ros_conv::compressImage(in, CompressionConfig{});
  EXPECT_EQ(z.format, "bgr8; jpeg compressed bgr8");
  EXPECT_LT(z.data.size(), in.data.size());
  const cv::Mat out = ros_conv::imageToBgr8(*ros_conv::decompressImage(z));
  EXPECT_LT(meanAbsDiff(out, testBgr()), 4.0);  // quality 80 on a smooth image: a few levels
}

TEST(CompressedTransport, GreyStaysGreyAndYuvArrivesAsItsBgr) {
  cv::Mat grey;
  cv::cvtColor(testBgr(), grey, cv::COLOR_BGR2GRAY);
  CompressionConfig png;
  png.format = "png";
  const sensor_msgs::ImagePtr g = ros_conv::decompressImage(
      ros_conv::compressImage(ros_conv::mono8ToImage(grey, header()), png));
  EXPECT_EQ(g->encoding, "mono8");
  EXPECT_EQ(meanAbsDiff(ros_conv::imageToMono8(*g), grey), 0.0);

  cv::Mat planes[3];
  cv::split(testBgr(), planes);  // any three planes make a valid UYVY image
  for (cv::Mat& p : planes) p.convertTo(p, CV_32F);
  const cv::Mat uyvy = color::packUyvy(planes[0], planes[1], planes[2]);
  const sensor_msgs::Image yuv = ros_conv::uyvyToImage(uyvy, header());
  const sensor_msgs::CompressedImage z = ros_conv::compressImage(yuv, png);
  EXPECT_EQ(z.format, "yuv422; png compressed bgr8");
  EXPECT_EQ(
      meanAbsDiff(ros_conv::imageToBgr8(*ros_conv::decompressImage(z)), ros_conv::imageToBgr8(yuv)),
      0.0);
}

TEST(CompressedTransport, RefusesWhatItCannotReadNamingWhy) {
  sensor_msgs::CompressedImage junk;
  junk.format = "bgr8; jpeg compressed bgr8";
  junk.data = {1, 2, 3, 4, 5};
  try {
    ros_conv::decompressImage(junk);
    FAIL() << "decoded 5 bytes of junk";
  } catch (const ros_conv::ImageFormatError& e) {
    EXPECT_NE(std::string(e.what()).find("not a JPEG or PNG"), std::string::npos) << e.what();
  }
  sensor_msgs::Image odd = ros_conv::bgr8ToImage(testBgr(), header());
  odd.encoding = "32FC1";
  EXPECT_THROW(ros_conv::compressImage(odd, CompressionConfig{}), ros_conv::ImageFormatError);
  CompressionConfig bad;
  bad.jpeg_quality = 0;
  try {
    ros_conv::compressImage(ros_conv::bgr8ToImage(testBgr(), header()), bad);
    FAIL() << "accepted jpeg_quality 0";
  } catch (const ros_conv::ImageFormatError& e) {
    EXPECT_NE(std::string(e.what()).find("jpeg_quality"), std::string::npos) << e.what();
  }
}

// A decompression bomb: a PNG's header can declare 32768 x 32768 pixels (a 1-bit PNG of that size
// is about 130 kB; decoded as bgr8 it is 3 GiB). The size is read from the header and the image
// refused before anything is decoded; a real image over a lowered limit is refused the same way,
// and one within it is decoded.
TEST(CompressedTransport, RefusesMorePixelsThanTheLimitBeforeDecoding) {
  std::vector<std::uint8_t> jpeg, png;
  cv::imencode(".jpg", testBgr(), jpeg);
  cv::imencode(".png", testBgr(), png);
  ASSERT_TRUE(io::encodedImageSize(jpeg));
  EXPECT_EQ(*io::encodedImageSize(jpeg), cv::Size(80, 60));
  ASSERT_TRUE(io::encodedImageSize(png));
  EXPECT_EQ(*io::encodedImageSize(png), cv::Size(80, 60));
  EXPECT_FALSE(io::encodedImageSize({0xff, 0xd8, 0xff}));  // a truncated JPEG
  // FF 00 is no marker: a reader that took its next bytes as a segment length could land on a
  // small frame hidden in the data while the decoder finds the real, large one.
  const std::uint8_t head[6] = {0xff, 0xd8, 0xff, 0x00, 0x00, 0x04};
  std::vector<std::uint8_t> stuffed(jpeg.size() + 4);
  std::copy(head, head + 6, stuffed.begin());
  std::copy(jpeg.begin() + 2, jpeg.end(), stuffed.begin() + 6);
  EXPECT_FALSE(io::encodedImageSize(stuffed));
  EXPECT_FALSE(io::encodedImageSize({}));

  sensor_msgs::CompressedImage bomb;
  bomb.format = "mono8; png compressed mono8";
  bomb.data = png;  // the header of a real PNG, its size changed to 32768 x 32768
  for (int k : {16, 20}) {
    bomb.data[k] = 0x00;
    bomb.data[k + 1] = 0x00;
    bomb.data[k + 2] = 0x80;
    bomb.data[k + 3] = 0x00;
  }
  EXPECT_EQ(*io::encodedImageSize(bomb.data), cv::Size(32768, 32768));
  try {
    ros_conv::decompressImage(bomb);
    FAIL() << "decoded a PNG declaring 32768 x 32768 pixels";
  } catch (const ros_conv::ImageFormatError& e) {
    EXPECT_NE(std::string(e.what()).find("1073741824 pixels) not decoded: more than the limit of "
                                         "50000000"),
              std::string::npos)
        << e.what();
  }
  sensor_msgs::CompressedImage real;
  real.format = "bgr8; png compressed bgr8";
  real.data = png;
  EXPECT_THROW(ros_conv::decompressImage(real, 80 * 60 - 1), ros_conv::ImageFormatError);
  EXPECT_EQ(ros_conv::decompressImage(real, 80 * 60)->width, 80u);
}
