#pragma once
// Where a lost target may be: places over a whole frame whose colours look like the target's, for
// the box tracker's re-detection (box_condensation_tracker.h, redetect_after_frames). The
// tracker then asks its correlation filter at each place and takes the target back only where the
// filter and the colours both answer as they did while it was followed.
//
// Contract: `likelihood` is P(O | c) over the whole frame (CV_32F, 0..1); a place's score is the
// box tracker's colour score of a box of `box_size` centred there (the mean of P inside minus the
// mean in the ring out to ring_scale times the box). Places are the centres of a grid half a box
// side apart (boxes wholly inside the frame); a place is returned when no place within one box
// side (in x and in y) scores higher; at most `count`, best first, each with its score. A box
// larger than the frame has no place.
#include <opencv2/core.hpp>
#include <vector>

namespace adaptive_perception::tracking {

struct ColourPlace {
  cv::Point2d centre;
  double score = 0.0;
};

std::vector<ColourPlace> colourPlaces(const cv::Mat& likelihood, const cv::Size2d& box_size,
                                      double ring_scale, int count);

}  // namespace adaptive_perception::tracking
