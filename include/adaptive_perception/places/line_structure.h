#pragma once
// Structural cues for room classification (papers/002 section 4.1.2, made general): the paper
// recognised hand-picked landmarks (the corridor ceiling's lines, the printer area's door squares)
// with a Hough transform. Here every image gets a line-structure descriptor instead, and training
// frames vote for their rooms by how similar their structure is, so no landmark is hand-picked.
//
// Descriptor: straight segments from the probabilistic Hough transform (cv::HoughLinesP) on Canny
// edges whose thresholds follow the image's own gradient distribution (so a darker image loses
// few edges), histogrammed by orientation (`orientation_bins` over [0, pi)) and by the vertical
// band of the segment's midpoint (`bands` equal bands), each segment weighted by its length over
// the image's width + height. The histogram is not normalised: its mass says how much structure
// the image has.
//
// Similarity of two descriptors: histogram intersection over the larger mass, in [0, 1] (1 for
// equal descriptors, 0 when either image has no segment).
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/places/feature_index.h"

namespace adaptive_perception::places {

struct LineStructureConfig {
  int orientation_bins = 12;      // over [0, pi), 2..90
  int bands = 3;                  // vertical bands of the image, 1..16
  double edge_percentile = 0.9;   // Canny high threshold = this quantile of gradient magnitude
  double low_to_high = 0.4;       // Canny low threshold = this x high, (0, 1]
  int hough_votes = 30;           // HoughLinesP accumulator threshold, >= 1
  double min_length_frac = 0.08;  // shortest segment, share of min(width, height), (0, 1]
  double max_gap_px = 3.0;        // HoughLinesP maxLineGap, >= 0
  int dims() const { return orientation_bins * bands; }
  void validate() const;  // throws std::invalid_argument naming the bad field
};

/// Hough segments of a bgr8 image (x1, y1, x2, y2), for display and tests.
std::vector<cv::Vec4i> detectLineSegments(const cv::Mat& bgr8, const LineStructureConfig& config);
/// The descriptor of a bgr8 image: 1 x dims() CV_32F (all zero when there is no segment).
cv::Mat lineStructure(const cv::Mat& bgr8, const LineStructureConfig& config);
/// The descriptor of given segments in an image of the given size.
cv::Mat lineStructureOf(const std::vector<cv::Vec4i>& segments, cv::Size image,
                        const LineStructureConfig& config);
/// Histogram intersection over the larger mass, in [0, 1]. Throws std::invalid_argument for
/// descriptors of different sizes.
double structureSimilarity(const cv::Mat& a, const cv::Mat& b);

/// How structural similarity joins the SIFT similarity of a frame (papers/002 section 4.1.3 put
/// the structural detection first; here both vote, weighted):
///   combined = (1 - weight) x sift + weight x max(0, (structure - floor) / (1 - floor)).
/// `floor` keeps the detection restrictive: frames less alike than it get no structural vote.
struct StructureVoteConfig {
  double weight = 0.0;  // 0 = structural cues off (the default), [0, 1]
  double floor = 0.6;   // structural similarity that counts as none, [0, 1)
  int candidates = 20;  // most structurally similar frames added to the SIFT candidates, >= 1
  bool enabled() const { return weight > 0.0; }
  void validate() const;  // throws std::invalid_argument naming the bad field
};

/// Joins per-frame SIFT similarities (frames not listed count as 0) with every frame's structural
/// similarity: the union of the SIFT frames and the `candidates` most structurally similar frames,
/// combined as above, most similar first, at most `n`.
std::vector<FrameMatch> combineStructure(const std::vector<FrameMatch>& sift,
                                         const std::vector<double>& structure,
                                         const StructureVoteConfig& config, int n);

}  // namespace adaptive_perception::places
