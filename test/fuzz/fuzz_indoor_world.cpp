// libFuzzer target: an indoor simulator world YAML (sim/indoor_world.h).
#include <cstdint>

#include "adaptive_perception/sim/indoor_world.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses(
      [&] { sim::IndoorWorld::loadYaml(fuzz::inputFile(data, size, ".yaml")); });
}
