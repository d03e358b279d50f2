#include "adaptive_perception/tracking/color_histogram.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "adaptive_perception/config/enum_names.h"

namespace adaptive_perception::tracking {

const config::EnumNames<ColorSpace>& colorSpaces() {
  static const config::EnumNames<ColorSpace> names(
      "color_space", {{ColorSpace::kRgb, "rgb"}, {ColorSpace::kOpponent, "opponent"}},
      {{ColorSpace::kOpponent, "bgr_opponent"}});
  return names;
}

ColorSpace parseColorSpace(const std::string& name) { return colorSpaces().parse(name); }
std::string colorSpaceName(ColorSpace space) { return colorSpaces().name(space); }

Eigen::Vector3f toColorSpace(const cv::Vec3b& bgr, ColorSpace space) {
  const float b = bgr[0], g = bgr[1], r = bgr[2];
  if (space == ColorSpace::kRgb) return Eigen::Vector3f(r, g, b) / 255.0f;
  return Eigen::Vector3f((b - g + 255.0f) / 510.0f, (g - r + 255.0f) / 510.0f,
                         (r + g + b) / 765.0f);
}

void Quantizer::validate() const {
  if (bins < 2 || bins > 64) throw std::invalid_argument("bins must be in 2..64");
}

int Quantizer::binOf(const Eigen::Vector3f& c) const {
  int idx[3];
  for (int k = 0; k < 3; ++k)
    idx[k] = std::clamp(static_cast<int>(c[k] * static_cast<float>(bins)), 0, bins - 1);
  return (idx[0] * bins + idx[1]) * bins + idx[2];
}

namespace {
// Integer arithmetic so a pixel's bin never depends on rounding.
inline int bgrBin(int B, int G, int R, int bins, bool rgb) {
  int i0, i1, i2;
  if (rgb) {
    i0 = std::min(bins - 1, R * bins / 255);
    i1 = std::min(bins - 1, G * bins / 255);
    i2 = std::min(bins - 1, B * bins / 255);
  } else {
    i0 = std::min(bins - 1, (B - G + 255) * bins / 510);
    i1 = std::min(bins - 1, (G - R + 255) * bins / 510);
    i2 = std::min(bins - 1, (R + G + B) * bins / 765);
  }
  return (i0 * bins + i1) * bins + i2;
}
}  // namespace

int Quantizer::binOf(const cv::Vec3b& bgr) const {
  return bgrBin(bgr[0], bgr[1], bgr[2], bins, space == ColorSpace::kRgb);
}

cv::Mat Quantizer::binImage(const cv::Mat& bgr8) const {
  validate();
  if (bgr8.type() != CV_8UC3) throw std::invalid_argument("binImage expects a bgr8 image");
  cv::Mat out(bgr8.size(), CV_32S);
  const bool rgb = space == ColorSpace::kRgb;
  for (int r = 0; r < bgr8.rows; ++r) {
    const cv::Vec3b* p = bgr8.ptr<cv::Vec3b>(r);
    int* o = out.ptr<int>(r);
    for (int c = 0; c < bgr8.cols; ++c) o[c] = bgrBin(p[c][0], p[c][1], p[c][2], bins, rgb);
  }
  return out;
}

Histogram histogramOf(const cv::Mat& bin_image, const cv::Mat& mask, int size) {
  if (bin_image.type() != CV_32S) throw std::invalid_argument("histogramOf: bin image not CV_32S");
  if (!mask.empty() && (mask.type() != CV_8U || mask.size() != bin_image.size()))
    throw std::invalid_argument("histogramOf: mask must be CV_8U of the bin image's size");
  Histogram h(size, 0.0f);
  for (int r = 0; r < bin_image.rows; ++r) {
    const int* b = bin_image.ptr<int>(r);
    const uchar* m = mask.empty() ? nullptr : mask.ptr<uchar>(r);
    for (int c = 0; c < bin_image.cols; ++c)
      if (!m || m[c]) h[b[c]] += 1.0f;
  }
  return h;
}

double intersection(const Histogram& candidate, const Histogram& model) {
  if (candidate.size() != model.size())
    throw std::invalid_argument("intersection: histograms of " + std::to_string(candidate.size()) +
                                " and " + std::to_string(model.size()) + " bins");
  double inter = 0.0, total = 0.0;
  for (size_t i = 0; i < candidate.size(); ++i) {
    inter += std::min(candidate[i], model[i]);
    total += candidate[i];
  }
  return total > 0.0 ? inter / total : 0.0;
}

void normalizeMass(Histogram* h, double mass) {
  const double total = std::accumulate(h->begin(), h->end(), 0.0);
  if (total <= 0.0) return;
  const float s = static_cast<float>(mass / total);
  for (float& v : *h) v *= s;
}

void updateModel(Histogram* model, const Histogram& candidate, double rate) {
  if (!(rate >= 0.0 && rate <= 1.0)) throw std::invalid_argument("updateModel: rate not in [0, 1]");
  if (model->size() != candidate.size())
    throw std::invalid_argument("updateModel: histograms of different sizes");
  Histogram c = candidate;
  normalizeMass(model, 1.0);
  normalizeMass(&c, 1.0);
  for (size_t i = 0; i < c.size(); ++i)
    (*model)[i] = static_cast<float>((1.0 - rate) * (*model)[i] + rate * c[i]);
}

}  // namespace adaptive_perception::tracking
