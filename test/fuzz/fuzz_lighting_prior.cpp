// libFuzzer target: a colour prior YAML (color/color_model.h, learn_color_priors output).
#include <cstdint>

#include "adaptive_perception/color/color_model.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses(
      [&] { color::LightingPrior::loadYaml(fuzz::inputFile(data, size, ".yaml")); });
}
