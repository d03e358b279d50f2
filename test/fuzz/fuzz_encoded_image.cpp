// libFuzzer target: a compressed image message's data (io/image_buffer.h's decodeImage, what the
// compressed transport's subscriber runs on every message). The first byte chooses grey or colour;
// the rest is the file. Decoding either returns an image of the size the header declared (or that
// size turned by a quarter) or throws ImageFormatError. The limit (4 megapixels) keeps what the
// decoder may allocate within a fuzzing run's memory; the refusal beyond it is the same at any
// limit.
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <vector>

#include "adaptive_perception/io/image_buffer.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const bool grey = data[0] & 1;
  const std::vector<std::uint8_t> file(data + 1, data + size);
  const std::optional<cv::Size> declared = io::encodedImageSize(file);
  return fuzz::parsesOrRefuses([&] {
    const cv::Mat image = io::decodeImage(file, grey, 4'000'000);
    // The size declared, or turned by a quarter (a JPEG's EXIF orientation is applied).
    const bool sized = declared && (image.size() == *declared ||
                                    image.size() == cv::Size(declared->height, declared->width));
    if (!sized || image.channels() != (grey ? 1 : 3)) std::abort();
  });
}
