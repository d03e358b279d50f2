// libFuzzer target: a field YAML (world/field_map.h).
#include <cstdint>

#include "adaptive_perception/world/field_map.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses(
      [&] { world::FieldMap::loadYaml(fuzz::inputFile(data, size, ".yaml")); });
}
