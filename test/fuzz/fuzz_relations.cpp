// libFuzzer target: a relations file of the SLAM benchmark (slam/relations.h).
#include <cstdint>

#include "adaptive_perception/slam/relations.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses(
      [&] { slam::readRelations(fuzz::inputFile(data, size, ".relations")); });
}
