#pragma once
// A discriminative correlation filter over gradient-orientation cells: the appearance cue of the
// box tracker (tracking/box_condensation_tracker.h), next to its colour distribution.
//
// Contract:
//  - A window `padding` times the target's box (same centre, same aspect) is resampled to a fixed
//    grid of cells (about `window_cells` a side in area), whatever the target's size in the image;
//    each cell holds `orientations` unsigned gradient-orientation energies (each normalised by its
//    3x3 neighbourhood's energy) and the mean grey level, under a Hann window.
//  - The filter is the closed-form ridge regression of those features onto a Gaussian peak at the
//    target's centre, solved per frequency with all channels sharing one denominator:
//        A_c = G . conj(X_c),   B = sum_c |X_c|^2,   response(Z) = F^-1[ sum_c A_c . Z_c / (B + lambda) ]
//    (capitals are 2-D DFTs; G that of the label). On its own training window the response is the
//    label itself up to the regularisation: 1 at zero displacement.
//  - `response()` answers on a window centred anywhere at any scale: element (row, col) of the map
//    is the score of the target centred `(col - cols/2, row - rows/2)` cells from the window's
//    centre (`cellPx(scale)` image pixels a cell).
//  - `update()` blends A and B towards those of a new window by `learning_rate` (the model
//    follows the target's appearance; the caller decides when it is trustworthy).
// Images: mono8 (CV_8UC1) or bgr8 (CV_8UC3, converted to grey on each call: a caller that asks
// several times a frame converts once); nothing is kept of the images.
#include <complex>
#include <opencv2/core.hpp>
#include <vector>

namespace adaptive_perception::tracking {

struct CorrelationFilterConfig {
  int window_cells = 32;       // the window's grid, cells a side if it were square, 8..128
  int cell_px = 4;             // pixels of the resampled window a cell, 2..16
  double padding = 2.5;        // window side / target side, 1.5..5
  // A small target's window is widened (up to max_padding) until its side (geometric mean) is
  // this many pixels: how far a target moves between frames does not shrink with its size.
  double min_window_px = 0.0;  // >= 0
  double max_padding = 5.0;    // >= padding
  int orientations = 9;        // unsigned gradient-orientation bins over 0..pi, 2..18
  double label_sigma = 0.1;    // sd of the Gaussian label, as a share of the target's side, > 0
  double lambda = 1e-2;        // ridge regularisation, > 0
  double learning_rate = 0.01; // of update(), [0, 1]
  void validate() const;       // throws std::invalid_argument naming the field
};

/// The cell features of a resampled grey window (CV_32F, values 0..1, size a multiple of
/// `cell_px`): one CV_32F map per channel, window.rows / cell_px x window.cols / cell_px:
/// `orientations` gradient-orientation energies, then the cells' mean grey level minus 0.5.
std::vector<cv::Mat> gradientCellFeatures(const cv::Mat& window, int cell_px, int orientations);
/// The window of `grey` (CV_8UC1) of size `window_px` (image pixels) centred at `centre`,
/// resampled to `out_size` pixels (CV_32F, 0..1), the image's border repeated beyond it; smoothed
/// before shrinking, so that the features change continuously with the window's size.
cv::Mat resampledWindow(const cv::Mat& grey, const cv::Point2d& centre, const cv::Size2d& window_px,
                        const cv::Size& out_size);

class CorrelationFilter {
 public:
  explicit CorrelationFilter(CorrelationFilterConfig config = {});
  /// Trains on `box` of `image`. Throws std::invalid_argument for an empty box or image.
  void init(const cv::Mat& image, const cv::Rect2d& box);
  bool initialized() const { return !a_.empty(); }

  /// The response map (CV_32F, rows() x cols()) of a window centred at `centre` whose target
  /// would be `scale` times the first box's size.
  cv::Mat response(const cv::Mat& image, const cv::Point2d& centre, double scale) const;
  /// The value of `map` (a response() about `centre` at `scale`) for the target centred at image
  /// point (x, y), bilinear between cells; 0 outside the map.
  double responseAt(const cv::Mat& map, const cv::Point2d& centre, double scale, double x,
                    double y) const;
  /// Blends the model towards the window centred at `centre` at `scale` (as above).
  void update(const cv::Mat& image, const cv::Point2d& centre, double scale);

  int rows() const { return rows_; }
  int cols() const { return cols_; }
  /// Image pixels a cell spans at `scale` (width, height).
  cv::Size2d cellPx(double scale) const {
    return {window_w0_px_ / cols_ * scale, window_h0_px_ / rows_ * scale};
  }
  const CorrelationFilterConfig& config() const { return config_; }

  /// The Hann-windowed features' spectra of the window at `centre`, `scale` (one per channel).
  std::vector<cv::Mat> spectra(const cv::Mat& image, const cv::Point2d& centre,
                               double scale) const;

 private:
  void train(const std::vector<cv::Mat>& x, double rate);

  CorrelationFilterConfig config_;
  int rows_ = 0, cols_ = 0;      // cells
  double window_w0_px_ = 0.0, window_h0_px_ = 0.0;  // the window at scale 1, image pixels
  double cell_scale_px_ = 0.0;   // image pixels a cell at scale 1
  cv::Mat hann_;                 // rows_ x cols_
  cv::Mat label_spectrum_;       // G, CV_32FC2
  std::vector<cv::Mat> a_;       // A_c, CV_32FC2
  cv::Mat b_;                    // B, CV_32F
};

}  // namespace adaptive_perception::tracking
