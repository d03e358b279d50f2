// libFuzzer target: a frame-correspondence CSV of a traversal pair (io/image_folder.h,
// readFrameCorrespondences: evaluate_places --ground_truth).
#include <cstdint>

#include "adaptive_perception/io/image_folder.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses(
      [&] { io::readFrameCorrespondences(fuzz::inputFile(data, size, ".csv")); });
}
