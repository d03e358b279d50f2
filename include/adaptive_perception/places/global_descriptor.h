#pragma once
// Whole-image descriptors for place recognition across light, beside the paper's colour
// histograms (histogram.h): each turns an image into one fixed-length row of bytes, compared by
// the mean absolute difference (L1 / length, in grey levels of the stored bytes), so that a query
// against N stored images is one pass of SIMD sums of absolute differences over an N x length
// matrix.
//
//   thumbnail     SeqSLAM's cue (Milford and Wyeth, ICRA 2012): the grey image area-resized to
//                 thumbnail_width_px x thumbnail_height_px and patch-normalised (each patch of
//                 patch_px x patch_px pixels to zero mean and unit standard deviation), so that a
//                 change of brightness, contrast or exposure that is smooth over a patch cancels.
//                 Stored as 128 + 32 z, clipped to [0, 255].
//   gradient      Histograms of oriented gradients (OpenCV's HOGDescriptor) over the grey image
//                 resized to hog_width_px x hog_height_px, cells of hog_cell_px, blocks of 2 x 2
//                 cells normalised L2-Hys (so a change of gain cancels), 9 unsigned orientations.
//                 Stored as 640 v, clipped.
//   chromaticity  Colour without intensity and without the light's colour: each channel divided by
//                 its mean over the image (grey-world), then the chromaticity r = R / (R + G + B),
//                 g = G / (R + G + B) of pixels brighter than 8 grey levels binned chroma_bins x
//                 chroma_bins, over the image's left and right halves. Stored as 255 sqrt(mass),
//                 so the L1 distance behaves like the Hellinger distance.
//
// A grey image (Nordland) has no chromaticity: every pixel falls in the grey bin, so the cue
// carries nothing there, as it should.
#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace adaptive_perception::places {

enum class DescriptorKind { kThumbnail = 0, kGradient = 1, kChromaticity = 2 };
constexpr int kNumDescriptorKinds = 3;

std::string descriptorName(DescriptorKind k);  // thumbnail, gradient, chromaticity
/// Throws std::invalid_argument listing the valid names.
DescriptorKind descriptorFromName(const std::string& name);

struct GlobalDescriptorConfig {
  int thumbnail_width_px = 64;  // SeqSLAM's 64 x 32 (Nordland ships at that size)
  int thumbnail_height_px = 32;
  int patch_px = 8;  // patch normalisation; must divide both thumbnail sides
  // Gradients of a 256 x 128 image in 32-px cells (8 x 4 cells, 756 bytes): at 128 x 64 the
  // gradients of a night image are mostly noise, and cells of an eighth of the width tolerate a
  // small sideways shift of the viewpoint (docs/places_across_light.md has the measurements).
  int hog_width_px = 256;  // multiples of hog_cell_px, at least 2 cells
  int hog_height_px = 128;
  int hog_cell_px = 32;
  int chroma_bins = 8;  // per chromaticity axis, 2..64

  void validate() const;  // throws std::invalid_argument naming the bad field
  /// Bytes of one descriptor of `kind` with these settings.
  int length(DescriptorKind kind) const;
  /// "thumbnail=64x32/8 gradient=256x128/32 chromaticity=8": what a stored descriptor was made
  /// with (two configurations agree when these strings do).
  std::string toString() const;
};

/// How the cues are weighed when fused (z-scores of each cue's distances, weighted mean). The
/// weights were chosen once on development data (docs/places_across_light.md).
struct FusionWeights {
  double thumbnail = 1.0;  // each >= 0, not all 0
  double gradient = 1.0;
  double chromaticity = 0.0;
  // The bag of SIFT words (traversal matching only, bag_of_words.h): 0, because across light it
  // adds nothing the other cues miss (docs/places_across_light.md).
  double words = 0.0;

  void validate() const;  // throws std::invalid_argument naming the bad field
};

/// True for "thumbnail", "gradient", "chromaticity" and "fused".
bool isCueName(const std::string& name);
/// The weight of each descriptor kind for a cue: a single descriptor's name gives 1 for it and 0
/// for the others, "fused" gives `fusion`. Throws std::invalid_argument for another name.
std::array<double, kNumDescriptorKinds> cueWeights(const std::string& cue,
                                                   const FusionWeights& fusion);

/// The descriptor of a bgr8 (CV_8UC3) or mono8 (CV_8UC1) image as one row (CV_8UC1, 1 x
/// length(kind)). Throws std::invalid_argument on another type or an empty image.
cv::Mat computeDescriptor(const cv::Mat& image, DescriptorKind kind,
                          const GlobalDescriptorConfig& config);

/// The descriptors of every kind of one image (rows indexed by DescriptorKind).
struct ImageDescriptors {
  std::vector<cv::Mat> rows;  // kNumDescriptorKinds rows
  cv::Mat sift;               // optional: N x 128 CV_32F SIFT descriptors (bag_of_words.h)
};
ImageDescriptors computeDescriptors(const cv::Mat& image, const GlobalDescriptorConfig& config);

/// Mean absolute difference per byte between `query` (1 x L) and every row of `stored` (N x L,
/// both CV_8UC1): N floats. Throws std::invalid_argument on a length or type mismatch.
std::vector<float> descriptorDistances(const cv::Mat& query, const cv::Mat& stored);

}  // namespace adaptive_perception::places
