// libFuzzer target: CARMEN log text (io/carmen_log.h).
#include <cstdint>
#include <string>

#include "adaptive_perception/io/carmen_log.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses(
      [&] { io::parseCarmenLog(std::string(reinterpret_cast<const char*>(data), size)); });
}
