// libFuzzer target: a CONDENSATION dynamics YAML (tracking/dynamics.h, learn_tracking_dynamics
// output).
#include <cstdint>

#include "adaptive_perception/tracking/dynamics.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses(
      [&] { tracking::Ar2Model::loadYaml(fuzz::inputFile(data, size, ".yaml")); });
}
