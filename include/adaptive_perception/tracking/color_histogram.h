#pragma once
// Colour histograms for tracking (papers/001 section 3): the colour spaces of the paper, the
// quantisation of an image into bin indices (done once per frame), histogram intersection (eq 28)
// and the model update (eq 29).
//
// Colours are points in the unit cube of the chosen space:
//   kRgb       (R, G, B) / 255, as in the paper's first experiment;
//   kOpponent  ((B - G + 255) / 510, (G - R + 255) / 510, (R + G + B) / 765): Birchfield's
//              (B-G, G-R, R+G+B), used by the paper for robustness to specular highlights.
// Bins: `bins` equal intervals per channel, bin (r, g, b) -> index (r * bins + g) * bins + b,
// value c in [0, 1] falling in interval min(floor(c * bins), bins - 1).
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "adaptive_perception/config/enum_names.h"

namespace adaptive_perception::tracking {

enum class ColorSpace { kRgb, kOpponent };
/// "rgb" | "opponent" (also "bgr_opponent"); throws std::invalid_argument naming the choices.
/// The colour spaces' words: "rgb", "opponent" (and the old spelling "bgr_opponent").
const config::EnumNames<ColorSpace>& colorSpaces();
ColorSpace parseColorSpace(const std::string& name);
std::string colorSpaceName(ColorSpace space);

/// One bgr8 pixel as a point of the unit cube of `space`.
Eigen::Vector3f toColorSpace(const cv::Vec3b& bgr, ColorSpace space);

struct Quantizer {
  ColorSpace space = ColorSpace::kOpponent;
  int bins = 16;  // per channel, 2..64
  int size() const { return bins * bins * bins; }
  int binOf(const Eigen::Vector3f& c) const;  // colour in the unit cube (clamped)
  int binOf(const cv::Vec3b& bgr) const;      // the same bin as binImage gives the pixel
  /// Bin index of every pixel of a bgr8 image (CV_32S, same size). Throws std::invalid_argument
  /// for another type.
  cv::Mat binImage(const cv::Mat& bgr8) const;
  void validate() const;  // throws std::invalid_argument naming the bad field
};

using Histogram = std::vector<float>;

/// Counts of the bins of `bin_image` pixels where `mask` (CV_8U, same size; empty = all) is set.
Histogram histogramOf(const cv::Mat& bin_image, const cv::Mat& mask, int size);

/// Eq 28: sum_i min(C(i), M(i)) / sum_i C(i); 0 when C is empty. Throws std::invalid_argument for
/// histograms of different sizes.
double intersection(const Histogram& candidate, const Histogram& model);

/// Eq 29: M <- (1 - a) M + a C, both normalised to unit mass first (a model of another ellipse
/// size stays comparable). `rate` a in [0, 1].
void updateModel(Histogram* model, const Histogram& candidate, double rate);

/// Scales a histogram to the given total mass (no change when it is empty).
void normalizeMass(Histogram* h, double mass);

}  // namespace adaptive_perception::tracking
