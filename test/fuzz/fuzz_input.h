#pragma once
// Shared by the fuzz targets (test/fuzz/fuzz_*.cpp): parsers that read a path get the fuzzer's
// bytes through a file of this process's own, rewritten for each input.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

namespace adaptive_perception::fuzz {

/// Writes the input to /tmp/ap_fuzz_<pid><suffix> and returns that path.
inline std::string inputFile(const std::uint8_t* data, std::size_t size,
                             const std::string& suffix) {
  const std::string path = "/tmp/ap_fuzz_" + std::to_string(::getpid()) + suffix;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace adaptive_perception::fuzz
