// libFuzzer target: a raw image message's header and data (io/image_buffer.h). The first 13 bytes
// give the encoding (one of the accepted ones, or the next bytes as a name), width, height and
// step; the rest is the pixel buffer. Every conversion either returns an image of the declared
// size or throws ImageFormatError; nothing reads past the buffer.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "adaptive_perception/io/image_buffer.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

namespace {
std::uint32_t word(const std::uint8_t* d) {
  return static_cast<std::uint32_t>(d[0]) | static_cast<std::uint32_t>(d[1]) << 8 |
         static_cast<std::uint32_t>(d[2]) << 16 | static_cast<std::uint32_t>(d[3]) << 24;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 13) return 0;
  static const char* kEncodings[] = {"bgr8", "rgb8", "mono8", "8UC1", "yuv422"};
  io::ImageBuffer image;
  std::size_t at = 13;
  if (data[0] < 250) {
    image.encoding = kEncodings[data[0] % 5];
  } else {  // a name of the input's own: up to 8 bytes
    const std::size_t n = std::min<std::size_t>(size - at, data[0] - 247u);
    image.encoding.assign(reinterpret_cast<const char*>(data + at), n);
    at += n;
  }
  image.width_px = word(data + 1);
  image.height_px = word(data + 5);
  image.step_bytes = word(data + 9);
  image.data = data + at;
  image.size_bytes = size - at;
  const auto check = [&](const cv::Mat& m) {
    if (m.cols != static_cast<int>(image.width_px) || m.rows != static_cast<int>(image.height_px))
      std::abort();  // an image of another size than declared
  };
  for (const std::int64_t limit : {io::kDefaultMaxImagePixels, std::int64_t{1} << 62}) {
    fuzz::parsesOrRefuses([&] { check(io::bufferToYuv(image, limit)); });
    fuzz::parsesOrRefuses([&] { check(io::bufferToBgr8(image, limit)); });
    fuzz::parsesOrRefuses([&] { check(io::bufferToMono8(image, limit)); });
  }
  return 0;
}
