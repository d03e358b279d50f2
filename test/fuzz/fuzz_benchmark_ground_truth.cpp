// libFuzzer target: a tracking benchmark's ground-truth file (io/benchmark_sequence.h), read as an
// OTB sequence of two frames.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "adaptive_perception/io/benchmark_sequence.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string dir = [] {
    const std::string d = fuzz::processPath("_sequence");
    fuzz::removeAtExit(d);
    std::filesystem::create_directories(d + "/img");
    for (const char* name : {"/img/0001.png", "/img/0002.png"})
      cv::imwrite(d + name, cv::Mat(4, 4, CV_8UC3, cv::Scalar(1, 2, 3)));
    return d;
  }();
  std::ofstream(dir + "/groundtruth_rect.txt", std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return fuzz::parsesOrRefuses([&] { io::readBenchmarkSequence(dir); });
}
