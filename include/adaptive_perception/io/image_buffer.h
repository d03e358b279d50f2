#pragma once
// Pixels from bytes that someone else laid out: a raw image buffer as a camera driver sends it (an
// encoding, a width, a height and a row step over a byte array) and an encoded JPEG or PNG file.
// The image nodes' message conversion (ros/msg_conversion.h) and the compressed transport
// (ros/compressed_transport.h) are thin wrappers of these, which keeps them ROS-free, unit-tested
// and fuzzed on their own (test/fuzz/fuzz_image_buffer.cpp, fuzz_encoded_image.cpp).
//
// Guarantees: every size is computed in 64 bits (a bgr8 width of 1431655766 is 4294967298 bytes a
// row, not 2); a buffer that does not hold what its header declares, an empty image, or more pixels
// than the caller's `max_pixels` is refused with ImageFormatError naming what was wrong, before any
// pixel is read or decoded. Nothing else is thrown for bad input: an exception of OpenCV's decoder
// (or its allocation) is turned into ImageFormatError. The returned images own their memory.
#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace adaptive_perception::io {

/// Thrown for an image the project cannot read; the message names the encoding or size problem.
class ImageFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The most pixels (width x height) an image may have before a node refuses it, unless its
/// ~max_image_pixels says otherwise: 50 megapixels, above any robot camera (8K UHD is 33.2 MP)
/// while a bgr8 copy stays under 150 MB. Written once here; the camera nodes' parameter, the
/// compressed transport's decoder and the image readers take it.
constexpr std::int64_t kDefaultMaxImagePixels = 50'000'000;

/// A raw image as a message carries it; the bytes are the caller's and are only read.
struct ImageBuffer {
  std::string encoding;  ///< ROS's names: bgr8, rgb8, mono8, 8UC1, yuv422 (UYVY)
  std::uint32_t width_px = 0;
  std::uint32_t height_px = 0;
  std::uint32_t step_bytes = 0;  ///< bytes from one row's start to the next
  const std::uint8_t* data = nullptr;
  std::size_t size_bytes = 0;
};

/// Per-pixel YUV (CV_8UC3, channels Y U V, BT.601 full range). Accepts yuv422, bgr8 and rgb8.
cv::Mat bufferToYuv(const ImageBuffer& image, std::int64_t max_pixels = kDefaultMaxImagePixels);
/// bgr8 (CV_8UC3). Accepts bgr8, rgb8, mono8 (the three channels equal) and yuv422.
cv::Mat bufferToBgr8(const ImageBuffer& image, std::int64_t max_pixels = kDefaultMaxImagePixels);
/// CV_8UC1. Accepts mono8 and 8UC1.
cv::Mat bufferToMono8(const ImageBuffer& image, std::int64_t max_pixels = kDefaultMaxImagePixels);

/// The width and height a PNG (its IHDR chunk) or JPEG (its first start-of-frame segment) file
/// declares, read from its header without decoding; nullopt for anything else, a truncated header,
/// or a zero size.
std::optional<cv::Size> encodedImageSize(const std::vector<std::uint8_t>& data);
/// The JPEG or PNG file decoded, as bgr8 or (`grey`) mono8. Its size is read from the header
/// first (a 130 kB PNG can declare 32768 x 32768 pixels, 3 GiB once decoded): refuses data that is
/// not such a file, one that declares more than `max_pixels` pixels, and one that fails to decode.
cv::Mat decodeImage(const std::vector<std::uint8_t>& data, bool grey,
                    std::int64_t max_pixels = kDefaultMaxImagePixels);

}  // namespace adaptive_perception::io
