// libFuzzer target: CARMEN log text (io/carmen_log.h).
#include <cstdint>
#include <exception>
#include <string>

#include "adaptive_perception/io/carmen_log.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    io::parseCarmenLog(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const std::exception&) {
    // A clear error is the expected answer to a bad file; crashes and sanitizer reports are not.
  }
  return 0;
}
