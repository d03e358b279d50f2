// libFuzzer target: a laser simulator world YAML (sim/laser_simulator.h).
#include <cstdint>
#include <exception>

#include "adaptive_perception/sim/laser_simulator.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    sim::LaserWorld::loadYaml(fuzz::inputFile(data, size, ".yaml"));
  } catch (const std::exception&) {
    // A clear error is the expected answer to a bad file; crashes and sanitizer reports are not.
  }
  return 0;
}
