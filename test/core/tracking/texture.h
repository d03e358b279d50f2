#pragma once
// The tracking tests' scene: a smooth random texture that gradient features and correlation filters
// can lock onto, the same for a seed.
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "adaptive_perception/math/rng.h"

namespace adaptive_perception::test_support {

/// A smooth random texture (grey, 8 bit): blurred uniform noise, stretched to 0..255.
inline cv::Mat texture(int cols, int rows, std::uint64_t seed) {
  math::Rng rng(seed);
  cv::Mat noise(rows, cols, CV_32F);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) noise.at<float>(r, c) = static_cast<float>(rng.uniform(0, 1));
  cv::GaussianBlur(noise, noise, cv::Size(), 2.0);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  cv::Mat out;
  noise.convertTo(out, CV_8U);
  return out;
}

}  // namespace adaptive_perception::test_support
