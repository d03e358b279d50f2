#include "adaptive_perception/places/histogram.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace adaptive_perception::places {
namespace {

const std::array<const char*, kNumSpaces> kSpaceNames = {
    "rgb", "normalized_rgb", "hsl", "normalized_hsl",
    "hsv", "normalized_hsv", "hsi", "normalized_hsi"};

// Hexagonal hue in [0, 1) (fraction of 360 deg); 0 for greys.
double hexHue(double r, double g, double b, double mx, double mn) {
  const double c = mx - mn;
  if (c <= 0.0) return 0.0;
  double h;
  if (mx == r)
    h = (g - b) / c;
  else if (mx == g)
    h = (b - r) / c + 2.0;
  else
    h = (r - g) / c + 4.0;
  h /= 6.0;
  if (h < 0.0) h += 1.0;
  return h >= 1.0 ? 0.0 : h;
}

}  // namespace

std::string spaceName(int space_index) {
  if (space_index < 0 || space_index >= kNumSpaces)
    throw std::invalid_argument("histogram space index " + std::to_string(space_index) +
                                " outside 0.." + std::to_string(kNumSpaces - 1));
  return kSpaceNames[space_index];
}

int spaceIndex(const std::string& name) {
  for (int i = 0; i < kNumSpaces; ++i)
    if (name == kSpaceNames[i]) return i;
  std::string valid;
  for (const char* n : kSpaceNames) valid += std::string(valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown colour space '" + name + "' (valid: " + valid + ")");
}

std::vector<int> parseSpaces(const std::string& list) {
  std::vector<int> out;
  if (list == "all") {
    for (int i = 0; i < kNumSpaces; ++i) out.push_back(i);
    return out;
  }
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(spaceIndex(item));
  if (out.empty()) throw std::invalid_argument("empty colour space list");
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::string spacesToString(const std::vector<int>& spaces) {
  std::string s;
  for (int i : spaces) s += (s.empty() ? "" : ",") + spaceName(i);
  return s;
}

std::array<double, 3> convertPixel(int space_index, double r, double g, double b) {
  if (space_index % 2 == 1) {  // eq. (1)
    const double sum = r + g + b;
    if (sum <= 0.0) {
      r = g = b = 1.0 / 3.0;
    } else {
      r /= sum;
      g /= sum;
      b /= sum;
    }
  }
  const double mx = std::max({r, g, b});
  const double mn = std::min({r, g, b});
  switch (static_cast<ColorSpace>(space_index / 2)) {
    case ColorSpace::kRgb:
      return {r, g, b};
    case ColorSpace::kHsl: {
      const double l = 0.5 * (mx + mn);
      const double denom = 1.0 - std::abs(2.0 * l - 1.0);
      const double s = (mx - mn) <= 0.0 || denom <= 0.0 ? 0.0 : std::min(1.0, (mx - mn) / denom);
      return {hexHue(r, g, b, mx, mn), s, l};
    }
    case ColorSpace::kHsv: {
      const double s = mx <= 0.0 ? 0.0 : (mx - mn) / mx;
      return {hexHue(r, g, b, mx, mn), s, mx};
    }
    case ColorSpace::kHsi: {
      const double i = (r + g + b) / 3.0;
      const double s = i <= 0.0 ? 0.0 : std::max(0.0, 1.0 - mn / i);
      double h = 0.0;
      const double num = 0.5 * ((r - g) + (r - b));
      const double den = std::sqrt((r - g) * (r - g) + (r - b) * (g - b));
      if (den > 1e-12) {
        const double theta = std::acos(std::clamp(num / den, -1.0, 1.0)) / (2.0 * M_PI);
        h = b <= g ? theta : 1.0 - theta;
        if (h >= 1.0) h = 0.0;
      }
      return {h, s, std::min(1.0, i)};
    }
  }
  throw std::invalid_argument("histogram space index " + std::to_string(space_index));
}

std::string MaskConfig::toString() const {
  switch (kind) {
    case Kind::kNone:
      return "none";
    case Kind::kAuto:
      return "auto";
    case Kind::kRing: {
      std::ostringstream os;
      os << "ring:" << center_x_px << "," << center_y_px << "," << inner_radius_px << ","
         << outer_radius_px;
      return os.str();
    }
  }
  return "none";
}

MaskConfig MaskConfig::parse(const std::string& text) {
  MaskConfig m;
  if (text == "none" || text.empty()) return m;
  if (text == "auto") {
    m.kind = Kind::kAuto;
    return m;
  }
  if (text.rfind("ring:", 0) == 0) {
    std::stringstream ss(text.substr(5));
    std::array<double, 4> v{};
    char sep = ',';
    for (int i = 0; i < 4; ++i) {
      if (i > 0 && (!(ss >> sep) || sep != ',')) break;
      if (!(ss >> v[i])) break;
      if (i == 3 && ss.peek() == EOF) {
        m.kind = Kind::kRing;
        m.center_x_px = v[0];
        m.center_y_px = v[1];
        m.inner_radius_px = v[2];
        m.outer_radius_px = v[3];
        m.validate();
        return m;
      }
    }
  }
  throw std::invalid_argument("mask '" + text +
                              "' is not one of: none, auto, ring:cx,cy,r_inner,r_outer (pixels)");
}

void MaskConfig::validate() const {
  if (kind == Kind::kRing && !(inner_radius_px >= 0.0 && outer_radius_px > inner_radius_px &&
                               std::isfinite(center_x_px) && std::isfinite(center_y_px)))
    throw std::invalid_argument("mask ring needs 0 <= inner_radius_px < outer_radius_px, got " +
                                toString());
  if (auto_black_level < 0 || auto_black_level > 254)
    throw std::invalid_argument("mask auto_black_level must be in 0..254");
}

MaskConfig detectRingMask(const cv::Mat& bgr8, int black_level) {
  if (bgr8.type() != CV_8UC3) throw std::invalid_argument("detectRingMask expects a bgr8 image");
  double sx = 0.0, sy = 0.0;
  long lit = 0;
  cv::Mat is_lit(bgr8.size(), CV_8UC1);
  for (int v = 0; v < bgr8.rows; ++v) {
    const cv::Vec3b* row = bgr8.ptr<cv::Vec3b>(v);
    uchar* out = is_lit.ptr<uchar>(v);
    for (int u = 0; u < bgr8.cols; ++u) {
      const bool on = std::max({row[u][0], row[u][1], row[u][2]}) > black_level;
      out[u] = on;
      if (on) {
        sx += u + 0.5;
        sy += v + 0.5;
        ++lit;
      }
    }
  }
  if (lit < 0.01 * bgr8.total())
    throw std::runtime_error("detectRingMask: fewer than 1% of the pixels are lit");
  const double cx = sx / lit, cy = sy / lit;
  const int max_r = static_cast<int>(std::ceil(std::hypot(bgr8.cols, bgr8.rows)));
  std::vector<long> on(max_r + 1, 0), all(max_r + 1, 0);
  for (int v = 0; v < bgr8.rows; ++v) {
    const uchar* row = is_lit.ptr<uchar>(v);
    for (int u = 0; u < bgr8.cols; ++u) {
      const int r = static_cast<int>(std::hypot(u + 0.5 - cx, v + 0.5 - cy));
      ++all[r];
      on[r] += row[u];
    }
  }
  int inner = -1, outer = -1;
  for (int r = 0; r <= max_r; ++r) {
    const bool mostly_lit = all[r] > 0 && 2 * on[r] >= all[r];
    if (mostly_lit && inner < 0) inner = r;
    if (mostly_lit) outer = r + 1;
  }
  MaskConfig m;
  m.kind = MaskConfig::Kind::kRing;
  m.center_x_px = cx;
  m.center_y_px = cy;
  m.inner_radius_px = inner + 2.0;
  m.outer_radius_px = std::max(m.inner_radius_px + 1.0, outer - 2.0);
  return m;
}

cv::Mat makeMask(const MaskConfig& config, const cv::Mat& bgr8) {
  config.validate();
  if (config.kind == MaskConfig::Kind::kNone) return cv::Mat();
  const MaskConfig ring = config.kind == MaskConfig::Kind::kAuto
                              ? detectRingMask(bgr8, config.auto_black_level)
                              : config;
  cv::Mat mask(bgr8.size(), CV_8UC1);
  const double r0 = ring.inner_radius_px * ring.inner_radius_px;
  const double r1 = ring.outer_radius_px * ring.outer_radius_px;
  for (int v = 0; v < mask.rows; ++v) {
    uchar* row = mask.ptr<uchar>(v);
    for (int u = 0; u < mask.cols; ++u) {
      const double dx = u + 0.5 - ring.center_x_px, dy = v + 0.5 - ring.center_y_px;
      const double d2 = dx * dx + dy * dy;
      row[u] = d2 >= r0 && d2 <= r1 ? 255 : 0;
    }
  }
  return mask;
}

void HistogramConfig::validate() const {
  if (bins < 2 || bins > 256)
    throw std::invalid_argument("bins must be in 2..256, got " + std::to_string(bins));
  if (spaces.empty()) throw std::invalid_argument("spaces: at least one colour space is needed");
  for (int s : spaces) spaceName(s);  // throws on a bad index
  mask.validate();
}

ImageHistograms computeHistograms(const cv::Mat& bgr8, const HistogramConfig& config) {
  config.validate();
  return computeHistograms(bgr8, makeMask(config.mask, bgr8), config.bins, config.spaces);
}

ImageHistograms computeHistograms(const cv::Mat& bgr8, const cv::Mat& mask, int bins,
                                  const std::vector<int>& spaces) {
  if (bgr8.type() != CV_8UC3)
    throw std::invalid_argument("computeHistograms expects a bgr8 (CV_8UC3) image");
  if (!mask.empty() && (mask.type() != CV_8UC1 || mask.size() != bgr8.size()))
    throw std::invalid_argument("computeHistograms: the mask must be CV_8UC1 of the image size");
  if (bins < 2 || bins > 256) throw std::invalid_argument("bins must be in 2..256");
  ImageHistograms out;
  out.bins = bins;
  std::vector<std::vector<double>> counts;
  for (int s : spaces) {
    spaceName(s);
    counts.emplace_back(3 * bins, 0.0);
  }
  const double inv255 = 1.0 / 255.0;
  long used = 0;
  for (int v = 0; v < bgr8.rows; ++v) {
    const cv::Vec3b* row = bgr8.ptr<cv::Vec3b>(v);
    const uchar* mrow = mask.empty() ? nullptr : mask.ptr<uchar>(v);
    for (int u = 0; u < bgr8.cols; ++u) {
      if (mrow && !mrow[u]) continue;
      ++used;
      const double r = row[u][2] * inv255, g = row[u][1] * inv255, b = row[u][0] * inv255;
      for (size_t k = 0; k < spaces.size(); ++k) {
        const std::array<double, 3> c = convertPixel(spaces[k], r, g, b);
        for (int band = 0; band < 3; ++band) {
          const int bin = std::clamp(static_cast<int>(c[band] * bins), 0, bins - 1);
          counts[k][band * bins + bin] += 1.0;
        }
      }
    }
  }
  if (used == 0) throw std::runtime_error("computeHistograms: the mask leaves no pixel");
  for (size_t k = 0; k < spaces.size(); ++k) {
    std::vector<float>& h = out.spaces[spaces[k]];
    h.resize(3 * bins);
    for (int i = 0; i < 3 * bins; ++i) h[i] = static_cast<float>(counts[k][i] / used);
  }
  return out;
}

}  // namespace adaptive_perception::places
