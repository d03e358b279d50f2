#include "adaptive_perception/color/white_balance.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::color {

const config::Fields<WhiteBalanceConfig>& WhiteBalanceConfig::fields() {
  using C = WhiteBalanceConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("white_balance_paint_share", &C::paint_share, config::closed(0, 1),
               "a paint pixel counts towards white when its luma is at least this share of the way "
               "from the carpet's to the paint's (95th percentile)")
          .add("white_balance_min_paint_pixels", &C::min_paint_pixels, config::closed(1, 100000000),
               "fewer paint pixels than this: no white balance")
          .add("white_balance_max_gain", &C::max_gain, config::closed(1, 100),
               "a channel gain beyond [1 / max_gain, max_gain] means the paint was not white: no "
               "balance")
          .add("white_balance_paint_luma", &C::paint_luma, config::closed(0, 255),
               "the paint's luma after the balance (the exposure the thresholds were set at); 0: "
               "its own")
          .add("white_balance_max_exposure_gain", &C::max_exposure_gain, config::closed(1, 100),
               "the exposure's gain (paint_luma over the paint's luma) is held within [1 / this, "
               "this]");
  return f;
}

namespace {

// The linear parts of BT.601 full range: YUV - (0, 128, 128) from RGB, and its inverse.
Eigen::Matrix3d fromRgb() {
  Eigen::Matrix3d m;
  for (int k = 0; k < 3; ++k)
    m.col(k) = rgbToYuv(Eigen::Vector3d::Unit(k)) - Eigen::Vector3d(0, 128, 128);
  return m;
}
Eigen::Matrix3d toRgb() {
  Eigen::Matrix3d m;
  for (int k = 0; k < 3; ++k)
    m.col(k) = yuvToRgb(Eigen::Vector3d::Unit(k) + Eigen::Vector3d(0, 128, 128));
  return m;
}

// `m` and the offset `t` as the 3x4 matrix cv::transform takes.
cv::Matx34f affine(const Eigen::Matrix3d& m, const Eigen::Vector3d& t) {
  cv::Matx34f a;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a(r, c) = static_cast<float>(m(r, c));
    a(r, 3) = static_cast<float>(t[r]);
  }
  return a;
}

}  // namespace

Eigen::Vector3d WhiteBalance::apply(const Eigen::Vector3d& yuv) const {
  if (identity) return yuv;
  const Eigen::Vector3d o(0, 128, 128);
  return fromRgb() * (gains_rgb.asDiagonal() * (toRgb() * (yuv - o))) + o;
}

cv::Mat WhiteBalance::apply(const cv::Mat& yuv) const {
  if (yuv.type() != CV_8UC3)
    throw std::invalid_argument("WhiteBalance::apply: expected a YUV (CV_8UC3) image, got type " +
                                std::to_string(yuv.type()));
  if (identity) return yuv.clone();
  // One affine map of YUV (R, G and B scaled, between the two conversions), saturated in YUV.
  const Eigen::Vector3d o(0, 128, 128);
  const Eigen::Matrix3d m = fromRgb() * gains_rgb.asDiagonal() * toRgb();
  cv::Mat out;
  cv::transform(yuv, out, affine(m, o - m * o));  // rounded and clipped to 0..255
  return out;
}

WhiteBalance whiteBalanceFromPaint(const cv::Mat& yuv, const FieldSegmentation& segmentation,
                                   const WhiteBalanceConfig& config) {
  config.validate();
  if (yuv.type() != CV_8UC3)
    throw std::invalid_argument("whiteBalanceFromPaint: expected a YUV (CV_8UC3) image, got type " +
                                std::to_string(yuv.type()));
  if (segmentation.labels.type() != CV_8UC1 || segmentation.labels.size() != yuv.size())
    throw std::invalid_argument(
        "whiteBalanceFromPaint: the segmentation's labels must be CV_8UC1 of the image's size (" +
        std::to_string(yuv.cols) + "x" + std::to_string(yuv.rows) + "), got type " +
        std::to_string(segmentation.labels.type()) + " " +
        std::to_string(segmentation.labels.cols) + "x" + std::to_string(segmentation.labels.rows));
  std::vector<cv::Vec3b> paint;
  for (int r = 0; r < yuv.rows; ++r) {
    const std::uint8_t* label = segmentation.labels.ptr<std::uint8_t>(r);
    const cv::Vec3b* px = yuv.ptr<cv::Vec3b>(r);
    for (int c = 0; c < yuv.cols; ++c)
      if (label[c] == world::kWhite) paint.push_back(px[c]);
  }
  WhiteBalance out;
  if (static_cast<int>(paint.size()) < config.min_paint_pixels) return out;
  // The paint's core: pixels at least paint_share paint, by luma, mixed linearly with the carpet
  // (a line's border pixel and the blur of a thin far line are part carpet).
  std::vector<int> lumas;
  lumas.reserve(paint.size());
  for (const cv::Vec3b& p : paint) lumas.push_back(p[0]);
  const auto top = lumas.begin() + static_cast<std::ptrdiff_t>(0.95 * (lumas.size() - 1));
  std::nth_element(lumas.begin(), top, lumas.end());
  const double carpet = segmentation.carpet_mean_yuv[0];
  const double bar = carpet + config.paint_share * (*top - carpet);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  int core = 0;
  for (const cv::Vec3b& p : paint)
    if (p[0] >= bar) mean += Eigen::Vector3d(p[0], p[1], p[2]), ++core;
  out.paint_pixels = core;
  if (core < config.min_paint_pixels) return out;
  mean /= static_cast<double>(core);
  out.white_yuv = mean;
  const Eigen::Vector3d rgb = yuvToRgb(mean);
  const double luma = mean[0];
  Eigen::Vector3d gains;
  for (int k = 0; k < 3; ++k) {
    if (rgb[k] <= 0.0) return out;
    gains[k] = luma / rgb[k];
    if (gains[k] > config.max_gain || gains[k] < 1.0 / config.max_gain) return out;
  }
  if (config.paint_luma > 0.0)
    gains *= std::clamp(config.paint_luma / luma, 1.0 / config.max_exposure_gain,
                        config.max_exposure_gain);
  out.identity = false;
  out.gains_rgb = gains;
  return out;
}

}  // namespace adaptive_perception::color
