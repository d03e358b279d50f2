#include "adaptive_perception/places/line_structure.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <unordered_map>

namespace adaptive_perception::places {

void LineStructureConfig::validate() const {
  if (orientation_bins < 2 || orientation_bins > 90)
    throw std::invalid_argument("orientation_bins must be in 2..90");
  if (bands < 1 || bands > 16) throw std::invalid_argument("bands must be in 1..16");
  if (!(edge_percentile > 0.0 && edge_percentile < 1.0))
    throw std::invalid_argument("edge_percentile must be in (0, 1)");
  if (!(low_to_high > 0.0 && low_to_high <= 1.0))
    throw std::invalid_argument("low_to_high must be in (0, 1]");
  if (hough_votes < 1) throw std::invalid_argument("hough_votes must be >= 1");
  if (!(min_length_frac > 0.0 && min_length_frac <= 1.0))
    throw std::invalid_argument("min_length_frac must be in (0, 1]");
  if (!(max_gap_px >= 0.0)) throw std::invalid_argument("max_gap_px must be >= 0");
}

void StructureVoteConfig::validate() const {
  if (!(weight >= 0.0 && weight <= 1.0)) throw std::invalid_argument("weight must be in [0, 1]");
  if (!(floor >= 0.0 && floor < 1.0)) throw std::invalid_argument("floor must be in [0, 1)");
  if (candidates < 1) throw std::invalid_argument("candidates must be >= 1");
}

std::vector<cv::Vec4i> detectLineSegments(const cv::Mat& bgr8, const LineStructureConfig& config) {
  config.validate();
  if (bgr8.type() != CV_8UC3 || bgr8.empty())
    throw std::invalid_argument("detectLineSegments expects a non-empty bgr8 image");
  cv::Mat grey, gx, gy, fx, fy, mag;
  cv::cvtColor(bgr8, grey, cv::COLOR_BGR2GRAY);
  cv::Sobel(grey, gx, CV_16S, 1, 0);
  cv::Sobel(grey, gy, CV_16S, 0, 1);
  gx.convertTo(fx, CV_32F);
  gy.convertTo(fy, CV_32F);
  cv::magnitude(fx, fy, mag);
  // The high threshold is a quantile of the gradient magnitude (a 256-bin histogram up to the
  // maximum), so it scales with the image's contrast.
  double max_mag = 0.0;
  cv::minMaxLoc(mag, nullptr, &max_mag);
  std::vector<cv::Vec4i> segments;
  if (max_mag <= 0.0) return segments;
  std::vector<int> hist(256, 0);
  const double to_bin = 255.0 / max_mag;
  for (int r = 0; r < mag.rows; ++r) {
    const float* m = mag.ptr<float>(r);
    for (int c = 0; c < mag.cols; ++c) ++hist[static_cast<int>(m[c] * to_bin)];
  }
  const long target = static_cast<long>(config.edge_percentile * mag.total());
  long cum = 0;
  int bin = 0;
  for (; bin < 255; ++bin) {
    cum += hist[bin];
    if (cum >= target) break;
  }
  // Canny on the same Sobel derivatives with the L2 gradient: its thresholds are in the units of
  // `mag`. The floor keeps sensor noise of a flat image from making edges.
  const double high = std::max(8.0, (bin + 1) / to_bin);
  cv::Mat edges;
  cv::Canny(gx, gy, edges, config.low_to_high * high, high, true);
  const double min_length = config.min_length_frac * std::min(bgr8.cols, bgr8.rows);
  cv::HoughLinesP(edges, segments, 1.0, CV_PI / 180.0, config.hough_votes, min_length,
                  config.max_gap_px);
  return segments;
}

cv::Mat lineStructureOf(const std::vector<cv::Vec4i>& segments, cv::Size image,
                        const LineStructureConfig& config) {
  config.validate();
  if (image.width <= 0 || image.height <= 0)
    throw std::invalid_argument("lineStructureOf: empty image size");
  cv::Mat out = cv::Mat::zeros(1, config.dims(), CV_32F);
  float* d = out.ptr<float>(0);
  const double norm = image.width + image.height;
  for (const cv::Vec4i& s : segments) {
    const double dx = s[2] - s[0], dy = s[3] - s[1];
    const double length = std::hypot(dx, dy);
    if (length <= 0.0) continue;
    double theta = std::atan2(dy, dx);  // (-pi, pi]; a line's orientation is modulo pi
    if (theta < 0.0) theta += CV_PI;
    if (theta >= CV_PI) theta -= CV_PI;
    const int o = std::min(config.orientation_bins - 1,
                           static_cast<int>(theta / CV_PI * config.orientation_bins));
    const double ymid = 0.5 * (s[1] + s[3]);
    const int b =
        std::clamp(static_cast<int>(ymid / image.height * config.bands), 0, config.bands - 1);
    d[b * config.orientation_bins + o] += static_cast<float>(length / norm);
  }
  return out;
}

cv::Mat lineStructure(const cv::Mat& bgr8, const LineStructureConfig& config) {
  return lineStructureOf(detectLineSegments(bgr8, config), bgr8.size(), config);
}

double structureSimilarity(const cv::Mat& a, const cv::Mat& b) {
  if (a.total() != b.total() || a.type() != CV_32F || b.type() != CV_32F)
    throw std::invalid_argument("structureSimilarity: descriptors of different sizes or types (" +
                                std::to_string(a.total()) + " and " + std::to_string(b.total()) +
                                " values)");
  const float* pa = a.ptr<float>();
  const float* pb = b.ptr<float>();
  double inter = 0.0, ma = 0.0, mb = 0.0;
  for (size_t i = 0; i < a.total(); ++i) {
    inter += std::min(pa[i], pb[i]);
    ma += pa[i];
    mb += pb[i];
  }
  const double m = std::max(ma, mb);
  return m > 0.0 && std::min(ma, mb) > 0.0 ? inter / m : 0.0;
}

std::vector<FrameMatch> combineStructure(const std::vector<FrameMatch>& sift,
                                         const std::vector<double>& structure,
                                         const StructureVoteConfig& config, int n) {
  config.validate();
  std::unordered_map<int, double> sift_of;
  for (const FrameMatch& m : sift) {
    if (m.frame < 0 || m.frame >= static_cast<int>(structure.size()))
      throw std::invalid_argument("combineStructure: frame " + std::to_string(m.frame) +
                                  " has no structural similarity");
    sift_of[m.frame] = m.similarity;
  }
  std::vector<int> order(structure.size());
  std::iota(order.begin(), order.end(), 0);
  const size_t k = std::min(order.size(), static_cast<size_t>(config.candidates));
  std::partial_sort(order.begin(), order.begin() + k, order.end(), [&](int a, int b) {
    return structure[a] > structure[b] || (structure[a] == structure[b] && a < b);
  });
  std::vector<int> frames;
  for (const FrameMatch& m : sift) frames.push_back(m.frame);
  frames.insert(frames.end(), order.begin(), order.begin() + k);
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  std::vector<FrameMatch> out;
  for (int f : frames) {
    const auto it = sift_of.find(f);
    const double s = it == sift_of.end() ? 0.0 : it->second;
    const double st = std::max(0.0, (structure[f] - config.floor) / (1.0 - config.floor));
    out.push_back({f, (1.0 - config.weight) * s + config.weight * st});
  }
  std::sort(out.begin(), out.end(), [](const FrameMatch& a, const FrameMatch& b) {
    return a.similarity > b.similarity || (a.similarity == b.similarity && a.frame < b.frame);
  });
  if (static_cast<int>(out.size()) > n) out.resize(n);
  return out;
}

}  // namespace adaptive_perception::places
