#pragma once
// White balance by the field's paint: the light's colour and brightness, measured on the one
// surface of a field that is white by the rules, divided out of the whole image (von Kries scaling
// of R, G and B), as a photographer's grey card is used.
//
// Why: a robot's camera balances its colours by its own guess (or not at all), and what it leaves
// (a warm evening light, a camera fixed to daylight) tints every colour the same way. The colour
// models' priors come from other venues, and the landmarks' hues and the goals' whiteness are read
// against them; a tint of a tenth of the channel's level moved the NAO development points' mirror
// decisions (docs/field_localization.md). The pose-free segmentation finds the line paint under any
// tint (it judges paleness against the carpet of the same image), and the paint's colour is the
// light's up to the camera's own gains. A dimmer light (or a camera's exposure fixed for another)
// scales every colour's chroma with its luma, and the thresholds that read hue and whiteness are in
// levels (a landmark's bands have 22-40 levels of chroma there, and under a light 0.7 times as
// bright two points' landmarks fell below LandmarkColourConfig::min_chroma's 15); so the balance
// also brings the paint to one luma, paint_luma.
//
// Contract: whiteBalanceFromPaint() takes the segmentation's paint pixels that are mostly paint
// (paint_share: a line's border mixes in the carpet), their mean in RGB (BT.601 full range, as
// color_space.h converts), and scales R, G and B each so that this mean becomes grey of its own
// luma; gains beyond [1 / max_gain, max_gain] are refused (no balance: what the segmentation took
// for paint was not white). Then all three are scaled by paint_luma over that luma (0: not),
// held within [1 / max_exposure_gain, max_exposure_gain]. With fewer than min_paint_pixels such
// pixels there is no balance (identity). The balance is one affine map of YUV (YUV and RGB are
// linear in each other), applied per pixel with rounding and clipping to 0..255 in YUV: a pixel
// pushed beyond white keeps its chroma (clipping in RGB instead was tried and not kept:
// docs/field_localization.md); deterministic.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "adaptive_perception/color/field_segmentation.h"
#include "adaptive_perception/config/fields.h"

namespace adaptive_perception::color {

struct WhiteBalanceConfig {
  /// A paint pixel counts towards white when its luma lies at least this share of the way from the
  /// carpet's mean luma to the paint's (its 95th percentile): a pixel mostly paint, mixed linearly
  /// with the carpet. The segmentation's paint takes in the border of a line and the blur of a
  /// thin far one, which are part carpet and would pull the white towards green.
  double paint_share = 0.5;
  /// Fewer paint pixels than this: no balance.
  int min_paint_pixels = 50;
  /// A channel's gain beyond [1 / max_gain, max_gain] means the "paint" was not white: no balance.
  /// 2: a light that halves one channel against another is already far from any hall's lamps
  /// and daylight once the camera has balanced at all.
  double max_gain = 2.0;
  /// The paint's luma after the balance. 220: where the paint's core lies on the NAO
  /// development images (214-244 at the four points not facing the windows' light), at which the
  /// localizer's thresholds in levels were set, and 35 levels below clipping. 0: the paint keeps
  /// its own luma (colour only).
  double paint_luma = 220.0;
  /// The exposure's gain (paint_luma over the paint's luma) is held within [1 / this, this]: a
  /// paint in deep shade or a dark frame is not brightened into noise.
  double max_exposure_gain = 2.0;

  static const config::Fields<WhiteBalanceConfig>& fields();
  void validate() const { fields().validate(*this); }
};

struct WhiteBalance {
  bool identity = true;
  Eigen::Vector3d gains_rgb = Eigen::Vector3d::Ones();       // R, G, B (colour and exposure)
  Eigen::Vector3d white_yuv = Eigen::Vector3d(0, 128, 128);  // the paint's mean it was taken from
  int paint_pixels = 0;                                      // paint pixels the mean was taken over

  /// `yuv` (CV_8UC3: Y, U, V) with R, G and B scaled by gains_rgb; a copy of it when identity.
  /// std::invalid_argument for another type.
  cv::Mat apply(const cv::Mat& yuv) const;
  /// One colour (Y, U, V) balanced, unrounded and unclipped.
  Eigen::Vector3d apply(const Eigen::Vector3d& yuv) const;
};

/// The balance that makes the paint segmentField found in `yuv` grey. std::invalid_argument when
/// the image is not CV_8UC3 or the labels are not CV_8UC1 of its size.
WhiteBalance whiteBalanceFromPaint(const cv::Mat& yuv, const FieldSegmentation& segmentation,
                                   const WhiteBalanceConfig& config);

}  // namespace adaptive_perception::color
