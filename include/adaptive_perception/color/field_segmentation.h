#pragma once
// Pose-free field segmentation: which pixels of a camera image are the field's carpet and which its
// painted lines, before the robot knows where it is (a robot at a new venue, a team calibrating).
//
// Contract: segmentField(image) labels every pixel world::kGreen (the field: the carpet
// inside the field's boundary and whatever stands on it), world::kWhite (a painted line) or
// world::kBackground (above the field's boundary). It needs no camera pose, no camera model and no
// earlier image; it is deterministic.
//
// Method (what the field's geometry says without a pose, then the two-level colour model):
//   1. The carpet's colour. A robot's camera looks at the field, so the carpet is the most common
//      green chroma (Cb < 128 and Cr < 128) in the image's lower part: the mode of the (U, V)
//      histogram there, the central share of its luma, seeds a Gaussian in YUV.
//   2. EM over the colour classes: a mixture of the carpet, the line paint (bright, neutral) and
//      everything else (two Gaussians: the image's overall colour and a dark neutral one, for goal
//      frames and shadows that a single broad class leaves to the carpet), the carpet's and the
//      paint's means pulled towards their seeds by a Gaussian prior as in the two-level model
//      (theta ~ N(seed, prior_std^2 I), pixel ~ N(theta, nu)).
//   3. The field's boundary: in each column the row below which carpet outweighs the rest (the
//      running sum from the bottom of +1 per carpet pixel, -boundary_other_weight per other pixel,
//      boundary_line_weight per paint pixel, restarted from zero where it falls below until carpet
//      first leads: the robot's own arm covering the image's bottom does not cancel the carpet
//      above it), chosen for all columns at once by dynamic programming with a cost per row of
//      step between neighbouring columns; then peaks narrower than boundary_min_width_share
//      removed (something field-coloured above the field: grass seen through a goal's net) and,
//      within that width of each side, where a peak's outer flank is out of view, a strip rising
//      above the boundary everywhere else (the other side's strip included) by more than that
//      width, so more steeply than 45 degrees, held down to the highest row there; then the upper
//      convex hull of the rows, since anything standing on the field can only hide the boundary,
//      never raise it, and the field seen from inside it is convex in the image.
//   4. Lines: inside the field, pixels paler than the carpet (chroma over luma) that are thin and
//      bright (a white top-hat of the smoothed luma with a window wider than a line, at least
//      line_contrast_sigma carpet standard deviations), with few objects (darker than the carpet
//      and of another chroma) about them, in strokes larger than line_min_area_share of the image
//      and at least line_min_elongation times as long as they are wide (grass texture and a
//      robot's white parts leave specks and blobs; paint is long and narrow).
//
// The defaults and the measurements that chose them: docs/field_segmentation.md.
#include <opencv2/core.hpp>

#include "adaptive_perception/config/fields.h"

namespace adaptive_perception::color {

struct FieldSegmentationConfig {
  /// Share of the image height, from the bottom, where the carpet's chroma is looked for.
  double seed_region_share = 0.5;
  /// The seed keeps the central share of its pixels' luma (0.5: the interquartile range), so that
  /// a wall or a floor of the carpet's chroma seen in the seed region does not widen the carpet's
  /// class (a goal's back wall took the carpet with it: field IoU 0.37 -> 0.81 on one image). The
  /// seed's luma spread is then that of the central share (about 0.14 of the variance for a
  /// Gaussian at 0.5); EM widens it to the carpet's (with em_iterations 0 it stays narrow).
  double seed_luma_share = 0.5;
  /// EM iterations of the colour mixture.
  int em_iterations = 8;
  /// EM runs on every n-th pixel in both directions.
  int em_stride_px = 4;
  /// Prior spread of each class mean around its seed (two-level model), 8-bit levels.
  double prior_std = 20.0;
  /// Weight of a line-paint pixel in the boundary's running sum (a carpet pixel counts +1).
  double boundary_line_weight = -0.5;
  /// Weight, negated, of a pixel of neither carpet nor paint in the running sum: 1 puts the
  /// boundary where carpet stops being the majority.
  double boundary_other_weight = 1.0;
  /// Cost of moving the boundary by one row from one column to the next, in pixels of the running
  /// sum (1: a row of boundary step costs as much as one pixel on the wrong side).
  double boundary_step_cost = 1.0;
  /// Replace the boundary by its upper convex hull.
  bool boundary_convex = true;
  /// Upward peaks of the boundary narrower than this share of the image width are removed.
  double boundary_min_width_share = 0.1;
  /// Top-hat window for the lines, as a share of the image width.
  double line_window_share = 0.03;
  /// A line pixel is at least this many carpet luma standard deviations above its surroundings.
  double line_contrast_sigma = 1.0;
  /// Standard deviation of the Gaussian smoothing of the luma before the top-hat, px.
  double line_blur_px = 1.5;
  /// Line strokes covering less than this share of the image are dropped.
  double line_min_area_share = 2e-4;
  /// Line strokes less elongated than this are dropped: a stroke's length is 4 standard deviations
  /// of its pixels along their major axis, its width its area over that length, and the ratio
  /// length / width (= length^2 / area) is about 1.33 l / t for a straight bar l long and t wide.
  /// 6: a bar at least about 4.5 times as long as wide. The shortest painted lines of a field are
  /// far longer (a goal area's 0.6 m sides of 0.05 m paint, 12 times), and stay so in perspective
  /// until seen nearly end-on; the grass's bright blades, a ball's panels and a robot's torso are
  /// not. The penalty marks (crosses of 0.1 m bars, 1.33) are dropped too. 0 turns it off.
  double line_min_elongation = 6.0;
  /// A line pixel lies on the carpet: within a square window of line_object_window_share of the
  /// image width about it (twice the top-hat's), at most line_max_object_share of the field's
  /// pixels are objects: darker than the carpet's mean and more than dark_chroma_sigma of the
  /// carpet's chroma standard deviations (Mahalanobis, U and V) from its chroma (3: the usual
  /// three sigma). A white robot, the ball and a shirt are bright and thin in places, as paint
  /// is, but rarely without dark parts of another colour than the carpet's beside them (joints,
  /// panels, hair, trousers). line_max_object_share 1 turns it
  /// off.
  double line_object_window_share = 0.06;
  double line_max_object_share = 0.1;
  double dark_chroma_sigma = 3.0;

  static const config::Fields<FieldSegmentationConfig>& fields();
  void validate() const;
};

struct FieldSegmentation {
  cv::Mat labels;        // CV_8UC1: world::kGreen, world::kWhite or world::kBackground
  cv::Mat boundary_row;  // CV_32SC1, 1 x width: the first field row of each column (rows: none)
  cv::Vec3d carpet_mean_yuv;  // the carpet's colour after EM (Y, U, V)
  cv::Vec3d line_mean_yuv;    // the line paint's colour after EM
};

/// Segments a BGR8 (CV_8UC3) image. Throws std::invalid_argument on an empty image or another
/// type.
FieldSegmentation segmentField(const cv::Mat& bgr, const FieldSegmentationConfig& config);
/// The same for a YUV image (CV_8UC3: Y, U, V, BT.601 full range, color/color_space.h), what the
/// nodes hold.
FieldSegmentation segmentFieldYuv(const cv::Mat& yuv, const FieldSegmentationConfig& config);

}  // namespace adaptive_perception::color
