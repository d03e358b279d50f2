#pragma once
// The one-pass evaluation (OPE) scores of the tracking benchmarks (Wu, Lim & Yang, "Online Object
// Tracking: A Benchmark", CVPR 2013), over the frames that have a true box:
//   success rate    share of frames whose box overlaps the truth with IoU >= 0.5;
//   success AUC     area under the success curve: the share of frames with IoU > t for the 21
//                   thresholds t = 0, 0.05, ..., 1, averaged (as the OTB toolkit computes it);
//   precision@20px  share of frames whose box centre lies within 20 pixels of the true centre.
// A frame the tracker reports lost, or gives no box for, has IoU 0 and an infinite centre error.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace adaptive_perception::tracking {

double boxIou(const cv::Rect2d& a, const cv::Rect2d& b);
double centreError(const cv::Rect2d& a, const cv::Rect2d& b);

/// Per frame: the tracker's box (nullopt: lost / none) and the truth (nullopt: not scored).
struct TrackScores {
  int frames_scored = 0;
  double success_rate = 0.0, auc = 0.0, precision_20px = 0.0, mean_iou = 0.0;
  std::vector<double> success_curve;    // 21 values, at IoU thresholds 0, 0.05, ..., 1
  std::vector<double> precision_curve;  // 51 values, at centre errors 0, 1, ..., 50 px
};

TrackScores scoreTrack(const std::vector<std::optional<cv::Rect2d>>& boxes,
                       const std::vector<std::optional<cv::Rect2d>>& truth);

}  // namespace adaptive_perception::tracking
