// libFuzzer target: a list of images with head angles, positions and torso pitches
// (io/head_image_list.h; evaluate_field_localization and field_images_to_bag --list).
#include <cstdint>

#include "adaptive_perception/io/head_image_list.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return fuzz::parsesOrRefuses([&] { io::readHeadImageList(fuzz::inputFile(data, size, ".csv")); });
}
