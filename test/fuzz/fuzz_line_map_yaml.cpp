// libFuzzer target: a saved line map (slam/map_io.h, readLineMapYaml), as ekf_slam_mapper's
// ~initial_map reads it.
#include <cstdint>

#include "adaptive_perception/slam/map_io.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses(
      [&] { slam::readLineMapYaml(fuzz::inputFile(data, size, "_line_map.yaml")); });
}
