#include "adaptive_perception/tracking/benchmark_metrics.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace adaptive_perception::tracking {

double boxIou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  const double uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0.0;
}

double centreError(const cv::Rect2d& a, const cv::Rect2d& b) {
  return std::hypot(a.x + a.width / 2 - (b.x + b.width / 2),
                    a.y + a.height / 2 - (b.y + b.height / 2));
}

TrackScores scoreTrack(const std::vector<std::optional<cv::Rect2d>>& boxes,
                       const std::vector<std::optional<cv::Rect2d>>& truth) {
  if (boxes.size() != truth.size())
    throw std::invalid_argument("scoreTrack: " + std::to_string(boxes.size()) + " boxes for " +
                                std::to_string(truth.size()) + " frames");
  TrackScores s;
  s.success_curve.assign(21, 0.0);
  s.precision_curve.assign(51, 0.0);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (!truth[i]) continue;
    ++s.frames_scored;
    const double iou = boxes[i] ? boxIou(*boxes[i], *truth[i]) : 0.0;
    const double err =
        boxes[i] ? centreError(*boxes[i], *truth[i]) : std::numeric_limits<double>::infinity();
    s.mean_iou += iou;
    s.success_rate += iou >= 0.5;
    s.precision_20px += err <= 20.0;
    for (int k = 0; k <= 20; ++k) s.success_curve[k] += iou > 0.05 * k;
    for (int k = 0; k <= 50; ++k) s.precision_curve[k] += err <= k;
  }
  if (s.frames_scored == 0) return s;
  const double n = s.frames_scored;
  s.mean_iou /= n;
  s.success_rate /= n;
  s.precision_20px /= n;
  for (double& v : s.success_curve) v /= n;
  for (double& v : s.precision_curve) v /= n;
  for (double v : s.success_curve) s.auc += v / 21.0;
  return s;
}

}  // namespace adaptive_perception::tracking
