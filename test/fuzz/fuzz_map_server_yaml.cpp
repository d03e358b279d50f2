// libFuzzer target: a map_server YAML (slam/occupancy_grid.h, readMapServerFiles) whose image key
// may name fuzz_map.pgm, a valid 4 x 3 PGM this target writes beside it: the YAML's keys and
// values are fuzzed (resolution, origin, thresholds, negate, mode, the image path), not the image
// decoder.
#include <cstdint>
#include <fstream>
#include <string>

#include "adaptive_perception/slam/occupancy_grid.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string dir = [] {
    const std::string d = fuzz::processPath("_map_server");
    std::filesystem::create_directories(d);
    fuzz::removeAtExit(d);
    std::ofstream pgm(d + "/fuzz_map.pgm", std::ios::binary);
    pgm << "P5\n4 3\n255\n";
    const unsigned char pixels[12] = {0, 254, 205, 0, 254, 205, 0, 254, 205, 0, 254, 205};
    pgm.write(reinterpret_cast<const char*>(pixels), sizeof pixels);
    return d;
  }();
  return fuzz::parsesOrRefuses([&] {
    const std::string path = dir + "/map.yaml";
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    slam::readMapServerFiles(path);
  });
}
