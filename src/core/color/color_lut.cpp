#include "adaptive_perception/color/color_lut.h"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

namespace adaptive_perception::color {

Eigen::Vector3d ColorLut::cellCentre(std::uint8_t y, std::uint8_t u, std::uint8_t v) {
  constexpr double kHalf = 0.5 * ((1 << kShift) - 1);
  return {double((y >> kShift) << kShift) + kHalf, double((u >> kShift) << kShift) + kHalf,
          double((v >> kShift) << kShift) + kHalf};
}

void ColorLut::build(const PixelClassifier& classifier) {
  constexpr double kStep = 1 << kShift;
  constexpr double kHalf = 0.5 * (kStep - 1);
  size_t i = 0;
  for (int y = 0; y < kCells; ++y)
    for (int u = 0; u < kCells; ++u)
      for (int v = 0; v < kCells; ++v)
        table_[i++] =
            classifier.classify({y * kStep + kHalf, u * kStep + kHalf, v * kStep + kHalf});
}

void ColorLut::classifyYuv(const cv::Mat& yuv, cv::Mat* labels) const {
  if (yuv.type() != CV_8UC3) throw std::invalid_argument("ColorLut::classifyYuv: expects CV_8UC3");
  labels->create(yuv.size(), CV_8UC1);
  for (int r = 0; r < yuv.rows; ++r) {
    const std::uint8_t* p = yuv.ptr<std::uint8_t>(r);
    std::uint8_t* o = labels->ptr<std::uint8_t>(r);
    for (int c = 0; c < yuv.cols; ++c) o[c] = lookup(p[3 * c], p[3 * c + 1], p[3 * c + 2]);
  }
}

void ColorLut::classifyUyvy(const cv::Mat& uyvy, cv::Mat* labels) const {
  if (uyvy.type() != CV_8UC2 || uyvy.cols % 2)
    throw std::invalid_argument("ColorLut::classifyUyvy: expects CV_8UC2, even width");
  labels->create(uyvy.size(), CV_8UC1);
  for (int r = 0; r < uyvy.rows; ++r) {
    const std::uint8_t* p = uyvy.ptr<std::uint8_t>(r);
    std::uint8_t* o = labels->ptr<std::uint8_t>(r);
    for (int c = 0; c < uyvy.cols; c += 2) {
      const std::uint8_t u = p[2 * c], y0 = p[2 * c + 1], v = p[2 * c + 2], y1 = p[2 * c + 3];
      o[c] = lookup(y0, u, v);
      o[c + 1] = lookup(y1, u, v);
    }
  }
}

bool ColorLutCache::update(const PixelClassifier& classifier) {
  bool rebuild = !built_ || built_from_.numColors() != classifier.numColors();
  for (int k = 0; !rebuild && k < classifier.numColors(); ++k) {
    const Eigen::Vector3d d = classifier.means()[k] - built_from_.means()[k];
    const double sigma = std::sqrt(built_from_.covs()[k].diagonal().minCoeff());
    const double det_ratio =
        classifier.covs()[k].determinant() / built_from_.covs()[k].determinant();
    rebuild = d.norm() > rebuild_sigma_ * sigma ||
              std::fabs(std::log(det_ratio)) > std::log1p(rebuild_sigma_);
  }
  if (!rebuild) return false;
  lut_.build(classifier);
  built_from_ = classifier;
  built_ = true;
  ++rebuilds_;
  return true;
}

}  // namespace adaptive_perception::color
