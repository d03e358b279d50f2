// libFuzzer target: an image-list CSV (io/image_list.h).
#include <cstdint>

#include "adaptive_perception/io/image_list.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses([&] { io::readImageList(fuzz::inputFile(data, size, ".csv")); });
}
