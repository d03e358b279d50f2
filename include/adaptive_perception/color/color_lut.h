#pragma once
// Fast colour classification: the current model compiled into a YUV lookup table (the colour
// paper's proposed future work). 6 bits per channel (64^3 cells of 4x4x4 levels, 256 KiB), each
// holding the class of its cell centre under PixelClassifier::classify. A frame is then one table
// read per pixel.
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/color/color_model.h"

namespace adaptive_perception::color {

class ColorLut {
 public:
  static constexpr int kBits = 6;
  static constexpr int kCells = 1 << kBits;
  static constexpr int kShift = 8 - kBits;

  ColorLut() : table_(kCells * kCells * kCells, 255) {}
  /// Fills the table from the classifier (cell centres).
  void build(const PixelClassifier& classifier);

  std::uint8_t lookup(std::uint8_t y, std::uint8_t u, std::uint8_t v) const {
    return table_[(static_cast<unsigned>(y >> kShift) << (2 * kBits)) |
                  (static_cast<unsigned>(u >> kShift) << kBits) | (v >> kShift)];
  }
  /// Class ids (CV_8UC1) of a per-pixel YUV image (CV_8UC3).
  void classifyYuv(const cv::Mat& yuv, cv::Mat* labels) const;
  /// Class ids of a packed UYVY image (CV_8UC2), without unpacking.
  void classifyUyvy(const cv::Mat& uyvy, cv::Mat* labels) const;

  /// The centre (Y, U, V) of the cell a value falls in.
  static Eigen::Vector3d cellCentre(std::uint8_t y, std::uint8_t u, std::uint8_t v);

 private:
  std::vector<std::uint8_t> table_;
};

/// Keeps a ColorLut in step with a changing model, rebuilding only when the model moved noticeably:
/// a colour mean moved by more than `rebuild_sigma` of its (eq. 9) standard deviation, or a
/// colour's covariance changed its determinant by more than a factor (1 + rebuild_sigma).
class ColorLutCache {
 public:
  explicit ColorLutCache(double rebuild_sigma = 0.2) : rebuild_sigma_(rebuild_sigma) {}
  /// Returns true when the table was rebuilt.
  bool update(const PixelClassifier& classifier);
  const ColorLut& lut() const { return lut_; }
  int rebuilds() const { return rebuilds_; }
  void setRebuildSigma(double s) { rebuild_sigma_ = s; }
  void invalidate() { built_ = false; }

 private:
  ColorLut lut_;
  PixelClassifier built_from_;
  bool built_ = false;
  double rebuild_sigma_;
  int rebuilds_ = 0;
};

}  // namespace adaptive_perception::color
