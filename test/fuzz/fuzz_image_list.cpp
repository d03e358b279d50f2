// libFuzzer target: an image-list CSV (io/image_list.h).
#include <cstdint>
#include <exception>

#include "adaptive_perception/io/image_list.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    io::readImageList(fuzz::inputFile(data, size, ".csv"));
  } catch (const std::exception&) {
    // A clear error is the expected answer to a bad file; crashes and sanitizer reports are not.
  }
  return 0;
}
