// libFuzzer target: a laser simulator world YAML (sim/laser_simulator.h).
#include <cstdint>

#include "adaptive_perception/sim/laser_simulator.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses(
      [&] { sim::LaserWorld::loadYaml(fuzz::inputFile(data, size, ".yaml")); });
}
