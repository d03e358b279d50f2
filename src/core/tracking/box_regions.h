#pragma once
// Region helpers shared by the box tracker's sources (box_condensation_tracker.cpp, the sampling
// and the estimate; box_colour_model.cpp, the colour histograms and the distractors). Internal:
// not installed, not part of the core's interface.
#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

namespace adaptive_perception::tracking::box_regions {


/// Sum of a CV_64F summed-area table over [x0, x1) x [y0, y1) (table coordinates).
inline double areaSum(const cv::Mat& sat, int x0, int y0, int x1, int y1) {
  return sat.at<double>(y1, x1) - sat.at<double>(y0, x1) - sat.at<double>(y1, x0) +
         sat.at<double>(y0, x0);
}

/// `box` grown about its centre by `factor` (side).
inline cv::Rect2d grown(const cv::Rect2d& box, double factor) {
  const double w = box.width * factor, h = box.height * factor;
  return {box.x + box.width / 2 - w / 2, box.y + box.height / 2 - h / 2, w, h};
}

/// Integer rectangle covering `r`, clipped to `bounds`.
inline cv::Rect covering(const cv::Rect2d& r, const cv::Rect& bounds) {
  const int x0 = static_cast<int>(std::floor(r.x)), y0 = static_cast<int>(std::floor(r.y));
  const int x1 = static_cast<int>(std::ceil(r.x + r.width));
  const int y1 = static_cast<int>(std::ceil(r.y + r.height));
  return cv::Rect(cv::Point(x0, y0), cv::Point(x1, y1)) & bounds;
}

/// The colour score of `box` (image coordinates) over a likelihood map whose summed-area table is
/// `sat` and whose top-left lies at `origin`: the mean inside minus the mean in the ring (the box
/// grown by ring_scale, minus the box); -1 for a box off the map.
inline double ringScore(const cv::Mat& sat, const cv::Point& origin, const cv::Rect2d& box,
                 double ring_scale) {
  const cv::Rect local(0, 0, sat.cols - 1, sat.rows - 1);
  const cv::Rect2d shifted(box.x - origin.x, box.y - origin.y, box.width, box.height);
  const cv::Rect in = covering(shifted, local);
  const cv::Rect ring = covering(grown(shifted, ring_scale), local);
  if (in.area() <= 0) return -1.0;
  const double s_in = areaSum(sat, in.x, in.y, in.x + in.width, in.y + in.height);
  const double s_ring =
      areaSum(sat, ring.x, ring.y, ring.x + ring.width, ring.y + ring.height) - s_in;
  const double a_ring = static_cast<double>(ring.area() - in.area());
  return s_in / in.area() - (a_ring >= 1.0 ? s_ring / a_ring : 0.0);
}

/// P(O | c) at every pixel of `bins` (the bin indices of a region) through `lut`, CV_32F.
inline cv::Mat lookUp(const cv::Mat& bins, const std::vector<float>& lut) {
  cv::Mat likelihood(bins.size(), CV_32F);
  for (int y = 0; y < bins.rows; ++y) {
    const std::uint16_t* in = bins.ptr<std::uint16_t>(y);
    float* o = likelihood.ptr<float>(y);
    for (int x = 0; x < bins.cols; ++x) o[x] = lut[in[x]];
  }
  return likelihood;
}

inline void normalize(std::vector<float>* h) {
  double sum = 0.0;
  for (float v : *h) sum += v;
  if (sum > 0)
    for (float& v : *h) v = static_cast<float>(v / sum);
}

}  // namespace adaptive_perception::tracking::box_regions
