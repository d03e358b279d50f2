// libFuzzer target: a traversal given as a CSV list of images (io/image_folder.h, readTraversal:
// evaluate_places --reference / --query).
#include <cstdint>

#include "adaptive_perception/io/image_folder.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses([&] { io::readTraversal(fuzz::inputFile(data, size, ".csv")); });
}
