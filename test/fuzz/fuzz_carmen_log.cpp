// libFuzzer target: CARMEN log text (io/carmen_log.h), and a bzip2 log (an input that starts with
// bzip2's magic `BZh`) through the file reader's decompression, under a 16 MiB limit.
#include <cstdint>
#include <cstring>
#include <string>

#include "adaptive_perception/io/carmen_log.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size >= 3 && std::memcmp(data, "BZh", 3) == 0) {
    io::CarmenReadOptions options;
    options.max_decompressed_bytes = std::uint64_t{16} << 20;
    fuzz::parsesOrRefuses(
        [&] { io::readCarmenLog(fuzz::inputFile(data, size, ".clf.bz2"), options); });
  }
  return fuzz::parsesOrRefuses(
      [&] { io::parseCarmenLog(std::string(reinterpret_cast<const char*>(data), size)); });
}
