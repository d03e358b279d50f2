// io::bufferTo* and io::decodeImage against pixels laid out by hand: row padding, channel order,
// UYVY pairs, and the refusals of io/image_buffer.h (sizes that wrap in 32 bits, short buffers,
// declared sizes beyond the limit), each checked to name what was wrong.
#include "adaptive_perception/io/image_buffer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "../refusal.h"

namespace ap = adaptive_perception;
using ap::io::ImageBuffer;
using ap::test_support::refusal;

namespace {

ImageBuffer buffer(const std::string& encoding, std::uint32_t width, std::uint32_t height,
                   std::uint32_t step, const std::vector<std::uint8_t>& bytes) {
  ImageBuffer b;
  b.encoding = encoding;
  b.width_px = width;
  b.height_px = height;
  b.step_bytes = step;
  b.data = bytes.data();
  b.size_bytes = bytes.size();
  return b;
}

/// Passes when `f()` throws io::ImageFormatError whose message contains `what`.
template <class F>
::testing::AssertionResult refused(F&& f, const std::string& what) {
  const std::string message = refusal<ap::io::ImageFormatError>(f);
  if (message != "accepted" && message.find(what) != std::string::npos)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "expected a refusal naming '" << what
                                       << "', got: " << message;
}

/// A PNG file's first 24 bytes (signature, IHDR length, "IHDR", width, height): no pixel data.
std::vector<std::uint8_t> pngHeader(std::uint32_t width, std::uint32_t height) {
  std::vector<std::uint8_t> d = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n',
                                 0,    0,   0,   13,  'I',  'H',  'D',  'R'};
  for (std::uint32_t v : {width, height})
    for (int shift = 24; shift >= 0; shift -= 8) d.push_back(static_cast<std::uint8_t>(v >> shift));
  return d;
}

}  // namespace

// A 2 x 2 bgr8 image whose rows are padded to 8 bytes: the padding is skipped, the copy owns its
// memory, and rgb8 swaps the first and third channels.
TEST(ImageBuffer, ReadsPaddedRowsInTheirChannelOrder) {
  const std::vector<std::uint8_t> bytes = {1, 2,  3,  4,  5,  6,  99, 99,
                                           7, 8,  9,  10, 11, 12, 99, 99};
  const cv::Mat bgr = ap::io::bufferToBgr8(buffer("bgr8", 2, 2, 8, bytes));
  ASSERT_EQ(bgr.type(), CV_8UC3);
  EXPECT_EQ(bgr.at<cv::Vec3b>(0, 1), cv::Vec3b(4, 5, 6));
  EXPECT_EQ(bgr.at<cv::Vec3b>(1, 0), cv::Vec3b(7, 8, 9));
  EXPECT_NE(bgr.data, bytes.data());
  const cv::Mat from_rgb = ap::io::bufferToBgr8(buffer("rgb8", 2, 2, 8, bytes));
  EXPECT_EQ(from_rgb.at<cv::Vec3b>(1, 1), cv::Vec3b(12, 11, 10));
  const std::vector<std::uint8_t> grey_bytes = {10, 20, 30, 0, 40, 50, 60, 0};
  const cv::Mat grey = ap::io::bufferToBgr8(buffer("mono8", 3, 2, 4, grey_bytes));
  EXPECT_EQ(grey.at<cv::Vec3b>(1, 2), cv::Vec3b(60, 60, 60));
  const cv::Mat mono = ap::io::bufferToMono8(buffer("8UC1", 3, 2, 4, grey_bytes));
  ASSERT_EQ(mono.type(), CV_8UC1);
  EXPECT_EQ(mono.at<std::uint8_t>(1, 0), 40);
}

// UYVY carries U Y0 V Y1 for each pair of pixels; with U = V = 128 (no chroma) both pixels are
// grey at their own luma, in YUV and in BGR alike.
TEST(ImageBuffer, UnpacksUyvyPairs) {
  const std::vector<std::uint8_t> bytes = {128, 50, 128, 200};
  const cv::Mat yuv = ap::io::bufferToYuv(buffer("yuv422", 2, 1, 4, bytes));
  EXPECT_EQ(yuv.at<cv::Vec3b>(0, 0), cv::Vec3b(50, 128, 128));
  EXPECT_EQ(yuv.at<cv::Vec3b>(0, 1), cv::Vec3b(200, 128, 128));
  const cv::Mat bgr = ap::io::bufferToBgr8(buffer("yuv422", 2, 1, 4, bytes));
  EXPECT_EQ(bgr.at<cv::Vec3b>(0, 0), cv::Vec3b(50, 50, 50));
  EXPECT_EQ(bgr.at<cv::Vec3b>(0, 1), cv::Vec3b(200, 200, 200));
  EXPECT_TRUE(refused([&] { ap::io::bufferToYuv(buffer("yuv422", 1, 1, 4, bytes)); },
                      "odd width 1"));
}

// A bgr8 width of 1431655766 makes width x 3 = 4294967298 bytes a row, 2 in 32 bits: with no pixel
// limit the 64-bit row size refuses it; a side beyond int's range is refused before any cv::Mat.
TEST(ImageBuffer, SizesThatWrapIn32BitsAreRefused) {
  const std::vector<std::uint8_t> two = {0, 0};
  const std::int64_t no_limit = std::numeric_limits<std::int64_t>::max();
  EXPECT_TRUE(refused([&] { ap::io::bufferToBgr8(buffer("bgr8", 1431655766u, 1, 2, two)); },
                      "more than the limit of 50000000"));
  EXPECT_TRUE(refused(
      [&] { ap::io::bufferToBgr8(buffer("bgr8", 1431655766u, 1, 2, two), no_limit); },
      "buffer too small"));
  EXPECT_TRUE(refused(
      [&] { ap::io::bufferToYuv(buffer("yuv422", 0x80000002u, 1, 4, two), no_limit); },
      "buffer too small"));
  // A buffer that holds such a row (its size only claimed here: nothing is read) still does not
  // make a cv::Mat of a negative column count.
  ImageBuffer wide = buffer("mono8", 0x80000002u, 1, 0x80000002u, two);
  wide.size_bytes = std::numeric_limits<std::size_t>::max();
  EXPECT_TRUE(refused([&] { ap::io::bufferToMono8(wide, no_limit); }, "beyond 2^31 - 1"));
  // step x height wraps to a small number in 32 bits: 0x80000000 x 2 = 2^32.
  EXPECT_TRUE(refused(
      [&] { ap::io::bufferToMono8(buffer("mono8", 1, 2, 0x80000000u, two), no_limit); },
      "buffer too small"));
  EXPECT_TRUE(refused([&] { ap::io::bufferToMono8(buffer("mono8", 0, 5, 1, two)); }, "empty"));
  ImageBuffer no_data = buffer("mono8", 1, 1, 1, two);
  no_data.data = nullptr;
  EXPECT_TRUE(refused([&] { ap::io::bufferToMono8(no_data); }, "buffer too small"));
  EXPECT_TRUE(refused([&] { ap::io::bufferToBgr8(buffer("bgr16", 1, 1, 6, two)); },
                      "unsupported image encoding 'bgr16'"));
  // At the limit it passes; one pixel over, it does not.
  const std::vector<std::uint8_t> six(6, 7);
  EXPECT_EQ(refusal<ap::io::ImageFormatError>([&] {
              ap::io::bufferToBgr8(buffer("bgr8", 2, 1, 6, six), 2);
            }),
            "accepted");
  EXPECT_TRUE(refused([&] { ap::io::bufferToBgr8(buffer("bgr8", 2, 1, 6, six), 1); }, "2 pixels"));
}

// An encoded file round-trips; its size comes from the header; a header that declares more than
// the limit is refused before decoding; anything else is refused as not decodable.
TEST(ImageBuffer, DecodesWhatItsHeaderAllows) {
  cv::Mat image(2, 3, CV_8UC3, cv::Scalar(10, 20, 30));
  image.at<cv::Vec3b>(1, 2) = cv::Vec3b(200, 100, 0);
  std::vector<std::uint8_t> png;
  ASSERT_TRUE(cv::imencode(".png", image, png));
  ASSERT_TRUE(ap::io::encodedImageSize(png));
  EXPECT_EQ(*ap::io::encodedImageSize(png), cv::Size(3, 2));
  const cv::Mat decoded = ap::io::decodeImage(png, false);
  ASSERT_EQ(decoded.size(), image.size());
  EXPECT_EQ(cv::norm(decoded, image, cv::NORM_INF), 0.0);
  EXPECT_EQ(ap::io::decodeImage(png, true).type(), CV_8UC1);
  EXPECT_TRUE(refused([&] { ap::io::decodeImage(png, false, 5); },
                      "3x2 (6 pixels) not decoded: more than the limit of 5"));
  // 32768 x 32768 declared by 24 bytes (3 GiB decoded): refused from the header alone.
  EXPECT_EQ(*ap::io::encodedImageSize(pngHeader(32768, 32768)), cv::Size(32768, 32768));
  EXPECT_TRUE(refused([&] { ap::io::decodeImage(pngHeader(32768, 32768), false); },
                      "1073741824 pixels) not decoded"));
  EXPECT_TRUE(refused([&] { ap::io::decodeImage(pngHeader(4, 4), false); },
                      "could not be decoded"));
  EXPECT_FALSE(ap::io::encodedImageSize(pngHeader(0, 4)));
  EXPECT_TRUE(refused([&] { ap::io::decodeImage({'G', 'I', 'F', '8'}, false); },
                      "not a JPEG or PNG file"));
}
