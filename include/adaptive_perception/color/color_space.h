#pragma once
// Colour spaces. The colour models work in YUV as robot cameras deliver it: ITU-R BT.601 with
// full-range 8-bit values (Y in 0..255, U and V centred on 128), the convention of the AIBO camera
// and of JPEG. Packed images are UYVY ("yuv422" in ROS): per pair of pixels U Y0 V Y1, chroma
// shared by the pair.
#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>

namespace adaptive_perception::color {

/// RGB in 0..255 (any range, linear map) -> YUV (BT.601 full range).
inline Eigen::Vector3d rgbToYuv(const Eigen::Vector3d& rgb) {
  const double r = rgb[0], g = rgb[1], b = rgb[2];
  return {0.299 * r + 0.587 * g + 0.114 * b, -0.168736 * r - 0.331264 * g + 0.5 * b + 128.0,
          0.5 * r - 0.418688 * g - 0.081312 * b + 128.0};
}

/// Inverse of rgbToYuv.
inline Eigen::Vector3d yuvToRgb(const Eigen::Vector3d& yuv) {
  const double y = yuv[0], u = yuv[1] - 128.0, v = yuv[2] - 128.0;
  return {y + 1.402 * v, y - 0.344136 * u - 0.714136 * v, y + 1.772 * u};
}

/// Packs three float planes Y, U, V (CV_32F, any value; clipped to 0..255 and rounded) into UYVY
/// (CV_8UC2, width must be even): each pair shares the mean of its two U and two V values.
cv::Mat packUyvy(const cv::Mat& y, const cv::Mat& u, const cv::Mat& v);

/// Unpacks UYVY (CV_8UC2) into a per-pixel YUV image (CV_8UC3, channels Y, U, V), the pair's chroma
/// repeated for both pixels.
cv::Mat unpackUyvy(const cv::Mat& uyvy);

/// BGR8 (CV_8UC3) of class ids (CV_8UC1) in the classes' display colours
/// (world::colorClassDisplayBgr).
cv::Mat colorizeLabels(const cv::Mat& labels);

/// Per-pixel YUV (CV_8UC3: Y, U, V, BT.601 full range, rounded) from BGR8 (CV_8UC3), as the nodes
/// convert a bgr8 image message; std::invalid_argument on another type.
cv::Mat bgrToYuv(const cv::Mat& bgr);
/// BGR8 (CV_8UC3) for display, from per-pixel YUV (CV_8UC3).
cv::Mat yuvToBgr(const cv::Mat& yuv);
/// BGR8 (CV_8UC3) for display, from UYVY.
cv::Mat uyvyToBgr(const cv::Mat& uyvy);

}  // namespace adaptive_perception::color
