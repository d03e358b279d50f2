// libFuzzer target: a field YAML (world/field_map.h).
#include <cstdint>
#include <exception>

#include "adaptive_perception/world/field_map.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    world::FieldMap::loadYaml(fuzz::inputFile(data, size, ".yaml"));
  } catch (const std::exception&) {
    // A clear error is the expected answer to a bad file; crashes and sanitizer reports are not.
  }
  return 0;
}
