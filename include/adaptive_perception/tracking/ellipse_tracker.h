#pragma once
// The elliptical head tracker of papers/001 section 3.2 (after Birchfield): the object is an
// axis-aligned ellipse whose colour histogram is compared with a model histogram by histogram
// intersection (eq 28). Each frame searches a window of centres (and, optionally, three sizes)
// around the previous ellipse for the best intersection; along a row of centres the histogram is
// updated incrementally (the pixels that leave the ellipse are subtracted, those that enter added,
// and the intersection sum follows bin by bin), so a candidate costs O(ellipse height), not
// O(ellipse area + bins). The model follows the light by eq 29, applied only when the best
// intersection is above `update_threshold`.
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/tracking/color_histogram.h"

namespace adaptive_perception::tracking {

struct Ellipse {
  double cx = 0.0, cy = 0.0;  // centre, pixels
  double ax = 1.0, ay = 1.0;  // semi-axes along x and y, pixels
  cv::Rect2d box() const { return {cx - ax, cy - ay, 2 * ax, 2 * ay}; }
  static Ellipse inscribed(const cv::Rect2d& box) {
    return {box.x + box.width / 2, box.y + box.height / 2, box.width / 2, box.height / 2};
  }
};

/// Half-width (pixels) of each row dy = -ry..ry of an ellipse with semi-axes ax, ay: the pixels
/// (cx + dx, cy + dy) with |dx| <= half-width are inside. ry = floor(ay).
std::vector<int> ellipseRowHalfWidths(double ax, double ay);

/// A filled ellipse window over a bin image: its histogram, its pixel count and its eq-28
/// intersection with a model held at a fixed mass, kept up to date as the window slides right.
class EllipseWindow {
 public:
  /// `bin_image` from Quantizer::binImage (kept by reference: it must outlive the window);
  /// `model` is scaled to the full ellipse's pixel count.
  EllipseWindow(const cv::Mat& bin_image, int bins, double ax, double ay, const Histogram& model);
  /// Recomputes the window centred at integer (cx, cy); pixels outside the image do not count.
  void place(int cx, int cy);
  /// Moves the centre one pixel right, incrementally.
  void shiftRight();
  const Histogram& histogram() const { return hist_; }
  double pixels() const { return pixels_; }
  /// Eq 28 against the model: sum min(C, M) / sum C.
  double intersection() const { return pixels_ > 0 ? inter_ / pixels_ : 0.0; }
  int cx() const { return cx_; }
  int cy() const { return cy_; }

 private:
  void add(int bin, float delta);
  const cv::Mat& bins_;
  std::vector<int> half_;
  Histogram model_, hist_;
  double inter_ = 0.0, pixels_ = 0.0;
  int cx_ = 0, cy_ = 0;
};

struct EllipseTrackerConfig {
  Quantizer quantizer{ColorSpace::kOpponent, 8};  // Birchfield's (B-G, G-R, R+G+B), 8 bins each
  int search_radius_px = 10;  // centres within +-this of the previous one, 1..200
  double scale_step = 0.0;    // also try sizes x (1 +- step), [0, 0.5); 0 = fixed size (the paper
                              // took the size from stereo; eq 28 alone favours shrinking)
  double update_rate = 0.1;   // a of eq 29, [0, 1]
  double update_threshold = 0.65;  // eq 29 only when the intersection is above this, [0, 1]
  double lost_threshold = 0.35;    // below this intersection the target is reported lost, [0, 1]
  double lost_search_gain = 3.0;   // the search radius grows by this factor while lost, >= 1
  double min_axis_px = 4.0;        // smallest semi-axis searched, > 0
  /// The fields condensation_tracker sets (config/fields.h: ~ellipse_*); defined in
  /// tracker_configs.cpp.
  static const config::Fields<EllipseTrackerConfig>& fields();
  void validate() const;           // throws std::invalid_argument naming the bad field
};

struct EllipseResult {
  Ellipse ellipse;
  double intersection = 0.0;
  bool lost = false;
  bool model_updated = false;
};

class EllipseTracker {
 public:
  explicit EllipseTracker(EllipseTrackerConfig config = {});
  /// Takes the model histogram from the pixels inside `e` in a bgr8 image. Throws
  /// std::invalid_argument when the ellipse holds no pixel of the image.
  void init(const cv::Mat& bgr8, const Ellipse& e);
  /// Replaces the model (e.g. a bimodal skin + hair histogram), keeping the ellipse.
  void setModel(const Histogram& model);
  /// One frame: the search around the last ellipse.
  EllipseResult track(const cv::Mat& bgr8);
  /// The same on an already quantised frame (Quantizer::binImage with this config's quantizer).
  EllipseResult trackBins(const cv::Mat& bin_image);
  const Histogram& model() const { return model_; }
  const Ellipse& ellipse() const { return ellipse_; }
  bool initialized() const { return initialized_; }

 private:
  EllipseTrackerConfig config_;
  Histogram model_;  // unit mass
  Ellipse ellipse_;
  bool initialized_ = false;
  bool lost_ = false;
};

}  // namespace adaptive_perception::tracking
