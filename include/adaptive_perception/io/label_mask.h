#pragma once
// Ground-truth label masks as segmentation benchmarks ship them, read in place:
//
//   a grey PNG    each pixel's value is its class (0, 1, 2, ...);
//   a palette PNG the class is the palette index; OpenCV expands palettes to colour, so the colour
//                 is mapped back through the PASCAL VOC palette (index 1 (128, 0, 0), 2 (0, 128,
//                 0), 3 (128, 128, 0), ... in RGB), the palette such masks are written with.
//
// A mask of another size than its image is scaled to it by nearest neighbour when the two aspect
// ratios agree within `kMaxAspectMismatch` (a mask drawn at another resolution); otherwise it is
// refused. Every problem throws std::runtime_error naming the file.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace adaptive_perception::io {

/// Largest relative difference of width/height between an image and a mask that is scaled to it.
constexpr double kMaxAspectMismatch = 0.10;

/// The class of each pixel (CV_8UC1) of the mask at `path`, at `image_size`. `scaled` (if given)
/// says whether the mask had another size.
cv::Mat readLabelMask(const std::string& path, cv::Size image_size, bool* scaled = nullptr);

/// The PASCAL VOC palette's colour (B, G, R) for class `index` (0..255).
cv::Vec3b vocPaletteBgr(int index);

/// An image and its mask: the file of the same name stem (any image extension) in the mask folder.
struct MaskedImage {
  std::string image_path, mask_path;
};
/// The images of `images_dir` (io::listImages order) with their masks in `masks_dir`. Throws naming
/// the first image without a mask.
std::vector<MaskedImage> pairImagesWithMasks(const std::string& images_dir,
                                             const std::string& masks_dir);

}  // namespace adaptive_perception::io
