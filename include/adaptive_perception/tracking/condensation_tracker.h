#pragma once
// CONDENSATION over the target's colour distribution, fused with an affine snake (papers/001
// section 3.3, Figs 10-12).
//
// Each frame:
//  1. Factored sampling: N samples drawn with replacement by weight from the last set, each
//     propagated by the learnt dynamics s_t = A s'_t + B w (dynamics.h).
//  2. Per sample: the reference distribution C_{t-1} warped to the sample's parameters
//     (color_distribution.h) gives a histogram H; a pixel is target-coloured when its bin holds at
//     least `min_bin_count` warped colours. The segmentation is cleaned by an opening and a
//     closing; its blob is the connected component that overlaps the predicted contour most.
//     The affine snake starts from the predicted contour (r_{t-1} moved by the last displacement)
//     and is fitted to the blob's boundary. The weight is exp(-rho^2 / 2 sigma^2) with
//       rho = mu1 (1 - Phi_affine) + mu2 (1 - Phi_area) + mu3 (1 - Phi_quality),
//     Phi_affine the share of snake points on the blob boundary, Phi_area = 1 - |A~ - A| /
//     max(A~, A) with A the snake's area and A~ = A_{t-1} + mu (A_{t-1} - A_{t-2}) (the paper
//     prints the difference term; its congruence is one minus it), Phi_quality = max(0, 1 - |E - 1|
//     / euler_scale) with E the Euler number of the blob (holes lower it).
//  3. The contour is refined on the image's Canny edges masked by the dilated boundary of the best
//     sample's blob (grad I* = grad I . dil(grad S)); C_t becomes the colours inside it.
//
// Deviations from the paper: for speed, samples segment a region around the predicted contour
// (`roi_margin` times its size on each side), not the whole image. While the target is lost the
// region grows for `local_lost_frames` frames, then is the whole frame, where the largest blobs are
// tried with the snake re-placed on each (re-acquisition). After each frame the samples' centroid
// and magnitudes are pulled towards the measured C_t (while lost: the last one measured) by
// `anchor_rate` (their velocities kept), and magnitudes stay within `max_stretch` of C_t's, so the
// filter cannot wander off along a colour direction that the current clutter happens not to test,
// nor drift away from the appearance it has to re-acquire.
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/tracking/affine_snake.h"
#include "adaptive_perception/tracking/color_distribution.h"
#include "adaptive_perception/tracking/color_histogram.h"
#include "adaptive_perception/tracking/dynamics.h"

namespace adaptive_perception::tracking {

/// Default propagation noise (sd per step): centroid 0.02, magnitudes 0.005, angles 0.03 rad.
DistributionState defaultNoiseSd();
/// The default dynamics: constant velocity for the centroid, a random walk (A1 = I, A0 = 0) for the
/// magnitudes and the angles (a constant-velocity magnitude drifts without bound between the
/// measurements that would check it), noise defaultNoiseSd(). learnAr2 replaces it.
Ar2Model defaultDynamics();

struct CondensationConfig {
  Quantizer quantizer{ColorSpace::kOpponent, 16};
  int samples = 100;                  // N, 1..100000
  int contour_points = 48;            // snake points, 8..1000
  int max_distribution_points = 800;  // colours kept of C_t (evenly subsampled), 10..1e6
  double roi_margin = 0.75;           // search region: predicted box + this x size per side, >= 0
  int min_bin_count = 1;              // warped colours a bin needs to mark a pixel, >= 1
  int morph_radius_px = 1;            // opening and closing, 0..20 (0 = none)
  double mu_affine = 1.0;             // mu1, >= 0
  double mu_area = 1.0;               // mu2, >= 0
  double mu_quality = 0.5;            // mu3, >= 0
  double sigma = 0.35;                // of the weight, > 0
  double area_velocity = 1.0;         // mu of the area prediction, [0, 2]
  double euler_scale = 4.0;           // |E - 1| that makes Phi_quality 0, > 0
  double lost_weight = 0.1;           // best weight below this: lost, [0, 1)
  double min_area_px = 16.0;          // a smaller contour is no target, > 0
  int refine_dilate_px = 2;           // dilation of the best boundary masking Canny, 0..20
  double canny_low = 30.0, canny_high = 90.0;  // refinement edges (grey levels)
  int reacquire_blobs = 3;                     // largest blobs tried while lost, 1..50
  double contour_margin_px = 2.0;              // C_t: colours this far inside the contour, >= 0
  double anchor_rate = 0.5;   // samples' m and lambda pulled this far to C_t, [0, 1]
  double max_stretch = 4.0;   // a sample's lambda within [1/x, x] of C_t's, >= 1
  int local_lost_frames = 5;  // lost: search around the last contour this long first
  Ar2Model dynamics = defaultDynamics();
  AffineSnakeConfig snake;
  /// The fields condensation_tracker sets (config/fields.h: ~samples, ~bins, ~contour_points,
  /// ~sigma, ~lost_weight, ~roi_margin); defined in tracker_configs.cpp.
  static const config::Fields<CondensationConfig>& fields();
  void validate() const;  // throws std::invalid_argument naming the bad field
};

struct SampleScore {
  double weight = 0.0;  // exp(-rho^2 / 2 sigma^2), unnormalised
  double phi_affine = 0.0, phi_area = 0.0, phi_quality = 0.0;
  double area_px = 0.0;
  int euler = 0;
  Contour contour;  // the fitted snake
};

struct TrackingResult {
  Contour contour;
  cv::Rect2d box;
  cv::RotatedRect ellipse;                              // fitted to the contour
  DistributionState state = DistributionState::Zero();  // best sample
  ColorStats distribution;                              // of C_t
  SampleScore best;
  bool lost = false;
  cv::Rect roi;          // region the samples segmented
  cv::Mat segmentation;  // CV_8U frame-sized, 255 = target colour (best sample, inside roi)
  std::vector<DistributionState> samples;
  std::vector<double> weights;           // normalised
  std::vector<Contour> sample_contours;  // each sample's fitted snake (empty: no blob), as samples
};

class CondensationTracker {
 public:
  CondensationTracker(CondensationConfig config, std::uint64_t seed);
  /// Starts on the target inside `roi` of a bgr8 frame: C_0 from the ellipse inscribed in it,
  /// the contour from its segmentation. Throws std::invalid_argument when the roi is empty or
  /// outside the image.
  void init(const cv::Mat& bgr8, const cv::Rect& roi);
  TrackingResult track(const cv::Mat& bgr8);
  bool initialized() const { return !reference_.empty(); }
  const Contour& contour() const { return contour_; }
  const CondensationConfig& config() const { return config_; }

 private:
  struct Blobs;
  SampleScore score(const Blobs& blobs, const Contour& start, int label, double predicted_area,
                    cv::Mat* boundary, cv::Point* boundary_offset) const;
  void segment(const cv::Mat& roi_bins, const DistributionState& s, cv::Mat* seg) const;
  void setReference(const cv::Mat& bgr8, const Contour& c);

  CondensationConfig config_;
  math::Rng rng_;
  ColorPoints reference_;
  ColorStats reference_stats_;
  Contour contour_;
  Eigen::Vector2d velocity_ = Eigen::Vector2d::Zero();
  double area1_ = 0.0, area2_ = 0.0;
  std::vector<DistributionState> samples_, previous_;
  std::vector<double> weights_;
  bool lost_ = false;
  int lost_count_ = 0;
};

}  // namespace adaptive_perception::tracking
