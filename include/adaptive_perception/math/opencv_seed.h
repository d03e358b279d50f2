#pragma once
// OpenCV's own generator (cv::theRNG(): cv::kmeans and FLANN's randomised kd-trees draw from it)
// set to a fixed seed for one scope and restored after it, so that what is built inside is the
// same in every run whatever the process drew before, and the caller's stream is left as it was.
#include <opencv2/core.hpp>

#include <cstdint>

namespace adaptive_perception::math {

class ScopedOpenCvSeed {
 public:
  explicit ScopedOpenCvSeed(std::uint64_t seed) : saved_(cv::theRNG().state) {
    cv::theRNG().state = seed;
  }
  ~ScopedOpenCvSeed() { cv::theRNG().state = saved_; }
  ScopedOpenCvSeed(const ScopedOpenCvSeed&) = delete;
  ScopedOpenCvSeed& operator=(const ScopedOpenCvSeed&) = delete;

 private:
  std::uint64_t saved_;
};

}  // namespace adaptive_perception::math
