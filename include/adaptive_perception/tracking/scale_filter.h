#pragma once
// The target's scale from its own search: a one-dimensional correlation filter over scales, after
// Danelljan et al., "Accurate scale estimation for robust visual tracking" (BMVC 2014, DSST). The
// box tracker (box_condensation_tracker.h) finds where the target is; this says how large it is.
//
// Contract:
//  - A scale sample n (n = -(scales-1)/2 .. (scales-1)/2) is the patch about the target's centre
//    of the target's size times (1 + scale_step)^n, resized to one model size (the target's
//    aspect at model_area_px) and described by gradient-orientation cells
//    (correlation_filter.h's gradientCellFeatures): a column of d values, weighted by a Hann window
//    over the scales.
//  - The filter is the ridge regression of those columns onto a Gaussian label over the scales
//    (sd label_sigma_factor sqrt(scales) samples), per feature row and frequency, one denominator:
//        A_l = G . conj(F_l),   B = sum_l |F_l|^2,   y = F^-1[ sum_l A_l . Z_l / (B + lambda) ]
//    (capitals: DFTs over the scale index). Trained on a target, the response peaks at n = 0;
//    grown by a factor (1 + scale_step)^k, it peaks at n = k.
//  - estimate() returns that factor, the peak refined by a parabola through its neighbours, so the
//    caller multiplies the target's size by it (within a quarter of a step of the truth up to 5
//    steps out; farther, the Hann window pulls it towards 1: a 1.2 zoom reads 1.19).
//    update() blends A and B by learning_rate.
// Images: mono8 (CV_8UC1); patches reaching past the image repeat its border.
#include <opencv2/core.hpp>
#include <vector>

namespace adaptive_perception::tracking {

struct ScaleFilterConfig {
  // The literature's values (DSST): 33 scales 2% apart (a factor 1.9 from the smallest to the
  // largest), a model of at most 512 pixels, label sd sqrt(33) / 4 samples, lambda 0.01, a
  // learning rate of 0.025.
  int scales = 33;                 // odd, 3..129
  double scale_step = 0.02;        // (1 + step) between neighbouring scales, 0 < x < 0.5
  double model_area_px = 512.0;    // the patches' common size, pixels (its aspect the target's)
  double padding = 1.0;            // a sample's side / the target's side (DSST: the target alone)
  int cell_px = 4;                 // 2..16
  int orientations = 9;            // 2..18
  double label_sigma_factor = 0.25;  // > 0
  double lambda = 1e-2;            // > 0
  double learning_rate = 0.025;    // [0, 1]
  void validate() const;           // throws std::invalid_argument naming the field
};

class ScaleFilter {
 public:
  explicit ScaleFilter(ScaleFilterConfig config = {});
  /// Trains on the target of size `target_px` (width, height) centred at `centre`. Throws
  /// std::invalid_argument for an empty image, one not mono8, or a size below one pixel.
  void init(const cv::Mat& grey, const cv::Point2d& centre, const cv::Size2d& target_px);
  bool initialized() const { return !b_.empty(); }
  /// The factor by which the target centred at `centre`, last known at `target_px`, has grown.
  double estimate(const cv::Mat& grey, const cv::Point2d& centre,
                  const cv::Size2d& target_px) const;
  /// Blends the model towards the target at `centre` of size `target_px`.
  void update(const cv::Mat& grey, const cv::Point2d& centre, const cv::Size2d& target_px);
  const ScaleFilterConfig& config() const { return config_; }

 private:
  /// The scale samples' features (d x scales, CV_32F, Hann-weighted) and their DFTs per row.
  cv::Mat spectra(const cv::Mat& grey, const cv::Point2d& centre,
                  const cv::Size2d& target_px) const;
  void train(const cv::Mat& f, double rate);

  ScaleFilterConfig config_;
  cv::Size model_px_;  // the patches' size, a multiple of cell_px
  cv::Mat hann_;       // 1 x scales
  cv::Mat label_;      // G: 1 x scales, CV_32FC2
  cv::Mat a_;          // A: d x scales, CV_32FC2
  cv::Mat b_;          // B: 1 x scales, CV_32F
};

}  // namespace adaptive_perception::tracking
