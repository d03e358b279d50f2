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
//   layout        Where the bright and the dark are: the grey image's intensities histogram-
//                 equalised (so that any monotonic change of brightness, contrast or gamma over the
//                 whole image cancels), then a histogram of layout_bins equalised levels in each of
//                 a few regions, stored as 255 sqrt(mass) like chromaticity. A perspective image
//                 (omni_ring none): layout_columns x layout_rows regions of the image resized to
//                 32 px per region. An omni-directional image (omni_ring a ring or auto, as the
//                 colour histograms' mask): layout_sectors angular sectors of the ring, and of each
//                 level's histogram over the sectors the magnitudes of its discrete Fourier
//                 transform (frequencies 0 .. layout_sectors / 2), which do not change when the
//                 robot turns on the spot (the ring image rotates).
//
// A grey image (Nordland) has no chromaticity: every pixel falls in the grey bin, so the cue
// carries nothing there, as it should.
#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "adaptive_perception/places/histogram.h"

namespace adaptive_perception::places {

enum class DescriptorKind { kThumbnail = 0, kGradient = 1, kChromaticity = 2, kLayout = 3 };
constexpr int kNumDescriptorKinds = 4;

std::string descriptorName(DescriptorKind k);  // thumbnail, gradient, chromaticity, layout
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
  int layout_columns = 4;  // perspective regions across, 1..16
  int layout_rows = 2;     // perspective regions down, 1..16
  int layout_sectors = 16;  // omni-directional sectors, even, 4..64
  int layout_bins = 8;      // equalised grey levels per region, 2..64
  // none: a perspective image. A ring or auto (descriptorConfigForMask sets it from the colour
  // histograms' mask): an omni-directional image, described by sectors of that ring.
  MaskConfig omni_ring;

  void validate() const;  // throws std::invalid_argument naming the bad field
  /// Bytes of one descriptor of `kind` with these settings.
  int length(DescriptorKind kind) const;
  /// "thumbnail=64x32/8 gradient=256x128/32 chromaticity=8 layout=regions4x2/8": what a stored
  /// descriptor was made with (two configurations agree when these strings do).
  std::string toString() const;
};

/// How the cues are weighed when fused (z-scores of each cue's distances, weighted mean). The
/// weights were chosen once on development data (docs/places_across_light.md).
struct FusionWeights {
  double thumbnail = 1.0;  // each >= 0, not all 0
  double gradient = 1.0;
  double chromaticity = 0.0;
  double layout = 0.0;
  // The bag of SIFT words (traversal matching only, bag_of_words.h): 0, because across light it
  // adds nothing the other cues miss (docs/places_across_light.md).
  double words = 0.0;

  void validate() const;  // throws std::invalid_argument naming the bad field
};

/// The descriptor settings for images whose colour histograms use `mask`: the defaults, with
/// omni_ring = mask (a ring mask marks omni-directional images).
GlobalDescriptorConfig descriptorConfigForMask(const MaskConfig& mask);

/// True for "thumbnail", "gradient", "chromaticity", "layout" and "fused".
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
