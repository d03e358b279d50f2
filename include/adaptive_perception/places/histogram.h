#pragma once
// Colour-space histograms of Wood et al., "Robot self-localization using omni-directional histogram
// correlation" (papers/004), section 2: four colour spaces (RGB, HSL, HSV, HSI), each also in a
// normalised variant (eq. 1), and one histogram per colour band, normalised to unit mass.
//
// Band values are scaled to [0, 1] before binning: R, G, B / 255; hue / 360 deg; saturation,
// lightness, value and intensity as they are. A value v falls in bin min(bins - 1, floor(v *
// bins)), so with 256 bins an 8-bit RGB level X lands in bin X.
#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace adaptive_perception::places {

/// The paper's four colour spaces.
enum class ColorSpace { kRgb = 0, kHsl = 1, kHsv = 2, kHsi = 3 };

/// Eight histogram spaces: the four colour spaces, plain and normalised. Index = 2 * space +
/// normalised, so 0 rgb, 1 normalized_rgb, 2 hsl, 3 normalized_hsl, 4 hsv, 5 normalized_hsv,
/// 6 hsi, 7 normalized_hsi. "Normalised" applies eq. (1), N_x = X / (R + G + B), to the pixel's
/// R, G, B first (a black pixel becomes 1/3, 1/3, 1/3) and converts the result: it removes the
/// intensity, keeps the chromaticity.
constexpr int kNumSpaces = 8;
std::string spaceName(int space_index);
/// The index of a name above; throws std::invalid_argument listing the valid names.
int spaceIndex(const std::string& name);
/// Parses "all" or a comma-separated list of names into sorted unique indices.
std::vector<int> parseSpaces(const std::string& list);
std::string spacesToString(const std::vector<int>& spaces);

/// Converts one RGB pixel (each in [0, 1]) to the three bands of a histogram space, each in
/// [0, 1]. Hue (HSL, HSV: hexagonal hue; HSI: the geometric hue, acos formula) is 0 for greys.
/// HSV: S = (max - min) / max, V = max. HSL: L = (max + min) / 2, S = (max - min) / (1 - |2L - 1|).
/// HSI: I = (R + G + B) / 3, S = 1 - min / I.
std::array<double, 3> convertPixel(int space_index, double r, double g, double b);

/// Which pixels count. Omni-directional images: a ring between two radii around a centre (the
/// paper masks the black border and the dead centre of the donut image).
struct MaskConfig {
  enum class Kind { kNone, kRing, kAuto };
  Kind kind = Kind::kNone;
  double center_x_px = 0.0, center_y_px = 0.0;  // kRing only
  double inner_radius_px = 0.0, outer_radius_px = 0.0;
  // kAuto: a pixel is "lit" when its max(R, G, B) exceeds this level (8-bit); the ring is fitted
  // to the lit pixels (detectRingMask).
  int auto_black_level = 12;

  /// "none", "auto" or "ring:cx,cy,r_inner,r_outer" (pixels). parse() throws on anything else.
  std::string toString() const;
  static MaskConfig parse(const std::string& text);
  void validate() const;  // throws std::invalid_argument naming the bad field
  bool operator==(const MaskConfig& o) const { return toString() == o.toString(); }
};

/// A CV_8UC1 mask (255 = used) of an image size; empty for kNone. kAuto looks at `bgr8`.
cv::Mat makeMask(const MaskConfig& config, const cv::Mat& bgr8);
/// Fits the ring of an omni-directional image: centre at the centroid of the lit pixels, inner
/// and outer radius where the fraction of lit pixels on a circle crosses one half, then 2 px in
/// from each edge. Throws std::runtime_error when fewer than 1% of the pixels are lit.
MaskConfig detectRingMask(const cv::Mat& bgr8, int black_level = 12);

struct HistogramConfig {
  int bins = 256;                                   // per band, 2..256
  std::vector<int> spaces{0, 1, 2, 3, 4, 5, 6, 7};  // histogram spaces to compute (indices above)
  MaskConfig mask;

  void validate() const;  // throws std::invalid_argument naming the bad field
};

/// The histograms of one image: for each computed space, 3 * bins floats (band 0, band 1, band 2),
/// each band summing to 1. Spaces not computed are empty.
struct ImageHistograms {
  int bins = 0;
  std::array<std::vector<float>, kNumSpaces> spaces;
  bool has(int space) const { return !spaces[space].empty(); }
};

/// Histograms of a bgr8 image (CV_8UC3) over the mask's pixels. Throws std::invalid_argument for
/// another image type and std::runtime_error when the mask leaves no pixel.
ImageHistograms computeHistograms(const cv::Mat& bgr8, const HistogramConfig& config);
/// The same with a precomputed mask (CV_8UC1 of the image size, or empty for all pixels).
ImageHistograms computeHistograms(const cv::Mat& bgr8, const cv::Mat& mask, int bins,
                                  const std::vector<int>& spaces);

}  // namespace adaptive_perception::places
