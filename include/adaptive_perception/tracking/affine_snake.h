#pragma once
// The affine snake of papers/001 section 3.3: a closed contour of image points that may only
// deform by an affine transform of its starting shape (so a partly occluded or merged blob cannot
// pull it into a non-affine shape, Fig 12), fitted to a binary edge image; and the shape measures
// the CONDENSATION weight uses (contour area, the Euler number of a segmentation).
//
// Fitting: each contour point looks along its normal, up to `search_px` either way, for the
// nearest edge pixel; the affine transform of the starting contour that best maps the points onto
// their matches (least squares, damped towards the current transform) is applied; repeat until
// the points move less than `converged_px` or `iterations` are done.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace adaptive_perception::tracking {

using Contour = std::vector<Eigen::Vector2d>;  // closed: the last point joins the first
using Affine2 = Eigen::Matrix<double, 2, 3>;   // [A | t]: p -> A p + t

/// `n` points evenly spaced by arc length along a closed polygon (at least 3 vertices).
Contour resampleContour(const std::vector<cv::Point>& polygon, int n);
/// `n` points on an ellipse.
Contour ellipseContour(double cx, double cy, double ax, double ay, int n);
double contourArea(const Contour& c);               // shoelace, absolute, pixels^2
Eigen::Vector2d contourCentroid(const Contour& c);  // mean of the points
cv::Rect2d contourBox(const Contour& c);
Contour applyAffine(const Affine2& t, const Contour& c);
/// The filled contour as a CV_8U mask (255 inside) of `size`, shifted by -offset.
cv::Mat contourMask(const Contour& c, cv::Size size, cv::Point offset = {0, 0});

struct AffineSnakeConfig {
  int iterations = 12;        // at most, 1..1000
  int search_px = 10;         // along each normal, either way, 1..500
  double damping = 0.05;      // pull towards the current transform (share of the data term), >= 0
  double converged_px = 0.1;  // stop when no point moves more than this, > 0
  double on_edge_px = 1.0;    // a final point within this of an edge pixel counts as on it, >= 0
  void validate() const;      // throws std::invalid_argument naming the bad field
};

struct AffineSnakeFit {
  Contour contour;
  Affine2 transform = Affine2::Identity();  // from the starting contour
  double on_edge = 0.0;  // Phi_affine: share of the final points on an edge pixel
  int iterations = 0;
  int matched = 0;  // points that found an edge in the last iteration
};

/// Fits `start` (image coordinates) to `edges` (CV_8U, nonzero = edge) whose pixel (0, 0) is at
/// image position `offset`. With fewer than 6 matched points the contour stays where it is.
AffineSnakeFit fitAffineSnake(const Contour& start, const cv::Mat& edges, cv::Point offset,
                              const AffineSnakeConfig& config);

/// Share of contour points within `radius_px` of an edge pixel.
double onEdgeShare(const Contour& c, const cv::Mat& edges, cv::Point offset, double radius_px);

/// Euler number (objects minus holes) of a binary image (nonzero = object), objects 8-connected
/// and holes 4-connected, by Gray's bit-quad counts: E = (n(Q1) - n(Q3) - 2 n(QD)) / 4.
int eulerNumber(const cv::Mat& binary);

}  // namespace adaptive_perception::tracking
