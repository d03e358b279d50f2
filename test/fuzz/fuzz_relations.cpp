// libFuzzer target: a relations file of the SLAM benchmark (slam/relations.h).
#include <cstdint>
#include <exception>

#include "adaptive_perception/slam/relations.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    slam::readRelations(fuzz::inputFile(data, size, ".relations"));
  } catch (const std::exception&) {
    // A clear error is the expected answer to a bad file; crashes and sanitizer reports are not.
  }
  return 0;
}
