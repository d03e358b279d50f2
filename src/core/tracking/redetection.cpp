// The places a lost target may be (redetection.h), and the box tracker's whole-frame search over
// them (BoxCondensationTracker::redetect, box_condensation_tracker.h: redetect_after_frames).
#include "adaptive_perception/tracking/redetection.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "adaptive_perception/tracking/box_condensation_tracker.h"
#include "box_regions.h"

namespace adaptive_perception::tracking {

std::vector<ColourPlace> colourPlaces(const cv::Mat& likelihood, const cv::Size2d& box_size,
                                      double ring_scale, int count) {
  if (likelihood.empty() || likelihood.type() != CV_32F)
    throw std::invalid_argument("colourPlaces: expected a CV_32F likelihood map");
  if (!(box_size.width >= 1.0 && box_size.height >= 1.0) || count < 1)
    throw std::invalid_argument("colourPlaces: a box of at least 1 px and count >= 1");
  cv::Mat sat;
  cv::integral(likelihood, sat, CV_64F);
  const double step_x = std::max(1.0, box_size.width / 2);
  const double step_y = std::max(1.0, box_size.height / 2);
  if (box_size.width > likelihood.cols || box_size.height > likelihood.rows) return {};
  const int nx = static_cast<int>(std::floor((likelihood.cols - box_size.width) / step_x)) + 1;
  const int ny = static_cast<int>(std::floor((likelihood.rows - box_size.height) / step_y)) + 1;
  cv::Mat scores(ny, nx, CV_64F);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const cv::Rect2d box(i * step_x, j * step_y, box_size.width, box_size.height);
      scores.at<double>(j, i) = box_regions::ringScore(sat, {0, 0}, box, ring_scale);
    }
  // A grid cell is half a side: the places within one side are the two cells on each side.
  std::vector<ColourPlace> places;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double s = scores.at<double>(j, i);
      bool best = true;
      for (int dj = -2; dj <= 2 && best; ++dj)
        for (int di = -2; di <= 2 && best; ++di) {
          const int jj = j + dj, ii = i + di;
          if ((dj || di) && jj >= 0 && jj < ny && ii >= 0 && ii < nx)
            best = scores.at<double>(jj, ii) <= s && !(scores.at<double>(jj, ii) == s &&
                                                       (dj < 0 || (dj == 0 && di < 0)));
        }
      if (best)
        places.push_back({{i * step_x + box_size.width / 2, j * step_y + box_size.height / 2}, s});
    }
  std::sort(places.begin(), places.end(),
            [](const ColourPlace& a, const ColourPlace& b) { return a.score > b.score; });
  if (static_cast<int>(places.size()) > count) places.resize(count);
  return places;
}

bool BoxCondensationTracker::redetect(const cv::Mat& image, const cv::Mat& grey,
                                      const std::vector<float>& lut, double peak_now,
                                      double colour_now, Sample* found) const {
  const cv::Rect bounds(0, 0, image.cols, image.rows);
  cv::Mat bins;
  binImage(image, bounds, &bins);
  const cv::Mat likelihood = box_regions::lookUp(bins, lut);
  cv::Mat sat;
  cv::integral(likelihood, sat, CV_64F);
  const Sample target{estimate_.x, estimate_.y, reference_log_scale_, reference_log_aspect_};
  const cv::Rect2d box = boxOf(target);
  const double side = std::sqrt(box.width * box.height);
  const double scale = std::exp(target.log_scale);
  // Both cues as the target answered while it was followed, and better than where the estimate
  // is: the filter's peak sharp (APCE, the LMCF criterion, which a textured place without the
  // target does not reach however high its peak) and higher than the estimate's; the colours'
  // score at that peak.
  const double min_apce = config_.reliable_apce_ratio * reference_apce_;
  const double min_colour = std::max(colour_now, config_.reliable_peak_ratio * reference_colour_);
  double best_peak = -1e300;
  for (const ColourPlace& place :
       colourPlaces(likelihood, box.size(), config_.ring_scale, config_.redetect_places)) {
    if (std::hypot(place.centre.x - estimate_.x, place.centre.y - estimate_.y) < side) continue;
    const cv::Mat map = filter_.response(grey, place.centre, scale);
    double peak = 0.0;
    cv::Point at;
    double lo = 0.0;
    cv::minMaxLoc(map, &lo, &peak, nullptr, &at);
    cv::Mat d = map - lo;
    const double energy = cv::mean(d.mul(d))[0];
    const double apce = energy > 0.0 ? (peak - lo) * (peak - lo) / energy : 0.0;
    const cv::Size2d cell = filter_.cellPx(scale);
    const cv::Point2d centre(place.centre.x + (at.x - filter_.cols() / 2) * cell.width,
                             place.centre.y + (at.y - filter_.rows() / 2) * cell.height);
    const cv::Rect2d there(centre.x - box.width / 2, centre.y - box.height / 2, box.width,
                           box.height);
    const double colour = box_regions::ringScore(sat, {0, 0}, there, config_.ring_scale);
    if (apce >= min_apce && peak > peak_now && colour > min_colour && peak > best_peak &&
        std::hypot(centre.x - estimate_.x, centre.y - estimate_.y) >= side) {
      best_peak = peak;
      *found = {centre.x, centre.y, target.log_scale, target.log_aspect};
    }
  }
  return best_peak > -1e300;
}

}  // namespace adaptive_perception::tracking
