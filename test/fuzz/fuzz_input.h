#pragma once
// Shared by the fuzz targets (test/fuzz/fuzz_*.cpp): parsers that read a path get the fuzzer's
// bytes through a file of this process's own, rewritten for each input and removed at exit.
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

namespace adaptive_perception::fuzz {

/// `<temp dir>/ap_fuzz_<pid><suffix>`: a path of this process's own.
inline std::string processPath(const std::string& suffix) {
  return (std::filesystem::temp_directory_path() /
          ("ap_fuzz_" + std::to_string(::getpid()) + suffix))
      .string();
}

/// Removes `path` (a file or a folder with its contents) when the process exits normally.
inline void removeAtExit(const std::string& path) {
  struct Remover {
    std::vector<std::string> paths;
    ~Remover() {
      std::error_code ignored;
      for (const std::string& p : paths) std::filesystem::remove_all(p, ignored);
    }
  };
  static Remover remover;
  if (std::find(remover.paths.begin(), remover.paths.end(), path) == remover.paths.end())
    remover.paths.push_back(path);
}

/// Writes the input to processPath(suffix) and returns that path.
inline std::string inputFile(const std::uint8_t* data, std::size_t size,
                             const std::string& suffix) {
  const std::string path = processPath(suffix);
  removeAtExit(path);
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

/// Runs `parse` (a parser on the fuzzer's input) and returns libFuzzer's 0. A std::exception, a
/// clear refusal of a bad file, is the expected answer; crashes and sanitizer reports are not.
template <class Parse>
int parsesOrRefuses(Parse&& parse) {
  try {
    parse();
  } catch (const std::exception&) {
  }
  return 0;
}

}  // namespace adaptive_perception::fuzz
