#include "adaptive_perception/io/image_buffer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "adaptive_perception/color/color_space.h"

namespace adaptive_perception::io {

namespace {

/// Refuses a buffer that does not hold `height` rows of `width * bytes_per_pixel` bytes at its
/// step, or that has no pixel or more than `max_pixels`; all in 64 bits.
void checkBuffer(const ImageBuffer& image, int bytes_per_pixel, std::int64_t max_pixels) {
  const std::string size = std::to_string(image.width_px) + "x" + std::to_string(image.height_px);
  if (image.width_px == 0 || image.height_px == 0)
    throw ImageFormatError("image is empty (" + size + ")");
  const std::uint64_t pixels = static_cast<std::uint64_t>(image.width_px) * image.height_px;
  if (max_pixels < 0 || pixels > static_cast<std::uint64_t>(max_pixels))
    throw ImageFormatError("image " + size + " has " + std::to_string(pixels) +
                           " pixels, more than the limit of " + std::to_string(max_pixels));
  const std::uint64_t row = static_cast<std::uint64_t>(image.width_px) * bytes_per_pixel;
  const std::uint64_t needed = static_cast<std::uint64_t>(image.step_bytes) * image.height_px;
  if (image.step_bytes < row || image.size_bytes < needed || image.data == nullptr)
    throw ImageFormatError("image buffer too small for " + size + " " + image.encoding +
                           " (step " + std::to_string(image.step_bytes) + ", " +
                           std::to_string(image.size_bytes) + " bytes)");
  constexpr std::uint32_t kMaxSide = 0x7fffffffu;  // cv::Mat's rows and columns are int
  if (image.width_px > kMaxSide || image.height_px > kMaxSide)
    throw ImageFormatError("image " + size + " has a side beyond 2^31 - 1 pixels");
}

/// A view of the checked buffer (no copy: the caller copies or converts).
cv::Mat view(const ImageBuffer& image, int type) {
  return cv::Mat(static_cast<int>(image.height_px), static_cast<int>(image.width_px), type,
                 const_cast<std::uint8_t*>(image.data), image.step_bytes);
}

std::uint32_t bigEndian(const std::vector<std::uint8_t>& d, std::size_t at, int bytes) {
  std::uint32_t v = 0;
  for (int k = 0; k < bytes; ++k) v = (v << 8) | d[at + static_cast<std::size_t>(k)];
  return v;
}

cv::Mat toYuv(const ImageBuffer& image, std::int64_t max_pixels) {
  if (image.encoding == "yuv422") {
    checkBuffer(image, 2, max_pixels);
    if (image.width_px % 2 != 0)
      throw ImageFormatError("yuv422 image of odd width " + std::to_string(image.width_px));
    return color::unpackUyvy(view(image, CV_8UC2));
  }
  if (image.encoding == "bgr8" || image.encoding == "rgb8") {
    checkBuffer(image, 3, max_pixels);
    if (image.encoding == "bgr8") return color::bgrToYuv(view(image, CV_8UC3));
    cv::Mat bgr;
    cv::cvtColor(view(image, CV_8UC3), bgr, cv::COLOR_RGB2BGR);
    return color::bgrToYuv(bgr);
  }
  throw ImageFormatError("unsupported image encoding '" + image.encoding +
                         "' (accepted: yuv422, bgr8, rgb8)");
}

cv::Mat toBgr8(const ImageBuffer& image, std::int64_t max_pixels) {
  cv::Mat out;
  if (image.encoding == "bgr8" || image.encoding == "rgb8") {
    checkBuffer(image, 3, max_pixels);
    if (image.encoding == "bgr8")
      out = view(image, CV_8UC3).clone();
    else
      cv::cvtColor(view(image, CV_8UC3), out, cv::COLOR_RGB2BGR);
    return out;
  }
  if (image.encoding == "mono8") {  // grey: the three channels equal
    checkBuffer(image, 1, max_pixels);
    cv::cvtColor(view(image, CV_8UC1), out, cv::COLOR_GRAY2BGR);
    return out;
  }
  if (image.encoding == "yuv422") {
    const cv::Mat yuv = toYuv(image, max_pixels);
    out.create(yuv.size(), CV_8UC3);
    for (int r = 0; r < yuv.rows; ++r) {
      const cv::Vec3b* s = yuv.ptr<cv::Vec3b>(r);
      cv::Vec3b* o = out.ptr<cv::Vec3b>(r);
      for (int c = 0; c < yuv.cols; ++c) {
        const Eigen::Vector3d rgb = color::yuvToRgb(Eigen::Vector3d(s[c][0], s[c][1], s[c][2]));
        for (int k = 0; k < 3; ++k)
          o[c][2 - k] = static_cast<std::uint8_t>(std::clamp(std::lround(rgb[k]), 0L, 255L));
      }
    }
    return out;
  }
  throw ImageFormatError("unsupported image encoding '" + image.encoding +
                         "' (accepted: bgr8, rgb8, mono8, yuv422)");
}

cv::Mat toMono8(const ImageBuffer& image, std::int64_t max_pixels) {
  if (image.encoding != "mono8" && image.encoding != "8UC1")
    throw ImageFormatError("expected a mono8 image, got encoding '" + image.encoding + "'");
  checkBuffer(image, 1, max_pixels);
  return view(image, CV_8UC1).clone();
}

/// `convert(image)`, with what OpenCV or the allocator throws for an image that passed the checks
/// (cv::Exception, std::bad_alloc near a high pixel limit) as ImageFormatError.
template <class Convert>
cv::Mat guarded(const ImageBuffer& image, Convert&& convert) {
  try {
    return convert();
  } catch (const ImageFormatError&) {
    throw;
  } catch (const std::exception& e) {
    throw ImageFormatError("image " + std::to_string(image.width_px) + "x" +
                           std::to_string(image.height_px) + " " + image.encoding +
                           " not converted: " + e.what());
  }
}

}  // namespace

cv::Mat bufferToYuv(const ImageBuffer& image, std::int64_t max_pixels) {
  return guarded(image, [&] { return toYuv(image, max_pixels); });
}

cv::Mat bufferToBgr8(const ImageBuffer& image, std::int64_t max_pixels) {
  return guarded(image, [&] { return toBgr8(image, max_pixels); });
}

cv::Mat bufferToMono8(const ImageBuffer& image, std::int64_t max_pixels) {
  return guarded(image, [&] { return toMono8(image, max_pixels); });
}

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

cv::Mat decodeImage(const std::vector<std::uint8_t>& data, bool grey, std::int64_t max_pixels) {
  const std::optional<cv::Size> size = encodedImageSize(data);
  if (!size)
    throw ImageFormatError("compressed image (" + std::to_string(data.size()) +
                           " bytes) is not a JPEG or PNG file whose header gives its size");
  const std::int64_t pixels = static_cast<std::int64_t>(size->width) * size->height;
  if (pixels > max_pixels)
    throw ImageFormatError("compressed image of " + std::to_string(size->width) + "x" +
                           std::to_string(size->height) + " (" + std::to_string(pixels) +
                           " pixels) not decoded: more than the limit of " +
                           std::to_string(max_pixels));
  cv::Mat decoded;
  try {
    decoded = cv::imdecode(data, grey ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
  } catch (const std::exception& e) {  // cv::Exception, bad_alloc
    throw ImageFormatError("compressed image not decoded: " + std::string(e.what()));
  }
  if (decoded.empty())
    throw ImageFormatError("compressed image (" + std::to_string(data.size()) +
                           " bytes) could not be decoded");
  return decoded;
}

}  // namespace adaptive_perception::io
