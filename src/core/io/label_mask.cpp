#include "adaptive_perception/io/label_mask.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "adaptive_perception/io/image_folder.h"

namespace adaptive_perception::io {

cv::Vec3b vocPaletteBgr(int index) {
  // The VOC palette spreads the index's bits over the three channels, most significant first.
  int r = 0, g = 0, b = 0;
  for (int bit = 0, c = index; bit < 8; ++bit, c >>= 3) {
    r |= ((c >> 0) & 1) << (7 - bit);
    g |= ((c >> 1) & 1) << (7 - bit);
    b |= ((c >> 2) & 1) << (7 - bit);
  }
  return {static_cast<std::uint8_t>(b), static_cast<std::uint8_t>(g), static_cast<std::uint8_t>(r)};
}

cv::Mat readLabelMask(const std::string& path, cv::Size image_size, bool* scaled) {
  const cv::Mat raw = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (raw.empty())
    throw std::runtime_error(path + ": cannot read the mask (missing or not an image)");
  if (raw.depth() != CV_8U)
    throw std::runtime_error(path + ": the mask must hold 8-bit values (class ids), not " +
                             std::to_string(8 * raw.elemSize1()) + "-bit");
  cv::Mat mask;
  if (raw.channels() == 1) {
    mask = raw;
  } else if (raw.channels() == 3 || raw.channels() == 4) {
    std::map<std::uint32_t, std::uint8_t> index;  // BGR -> palette index
    for (int i = 0; i < 256; ++i) {
      const cv::Vec3b p = vocPaletteBgr(i);
      index.emplace((p[0] << 16) | (p[1] << 8) | p[2], static_cast<std::uint8_t>(i));
    }
    mask.create(raw.rows, raw.cols, CV_8UC1);
    const int step = raw.channels();
    for (int r = 0; r < raw.rows; ++r) {
      const std::uint8_t* in = raw.ptr<std::uint8_t>(r);
      for (int c = 0; c < raw.cols; ++c, in += step) {
        const auto it = index.find((in[0] << 16) | (in[1] << 8) | in[2]);
        if (it == index.end())
          throw std::runtime_error(path + ": pixel (" + std::to_string(c) + ", " +
                                   std::to_string(r) + ") has colour (" + std::to_string(in[2]) +
                                   ", " + std::to_string(in[1]) + ", " + std::to_string(in[0]) +
                                   ") RGB, not a class of the VOC palette (a grey or palette PNG "
                                   "of class ids is expected)");
        mask.at<std::uint8_t>(r, c) = it->second;
      }
    }
  } else {
    throw std::runtime_error(path +
                             ": a mask has 1 (class ids) or 3 (palette colours) channels, "
                             "not " +
                             std::to_string(raw.channels()));
  }
  const bool differs = mask.size() != image_size;
  if (scaled) *scaled = differs;
  if (!differs) return mask;
  const double a_mask = double(mask.cols) / mask.rows,
               a_image = double(image_size.width) / image_size.height;
  if (std::fabs(a_mask / a_image - 1.0) > kMaxAspectMismatch)
    throw std::runtime_error(path + ": the mask is " + std::to_string(mask.cols) + " x " +
                             std::to_string(mask.rows) + ", its image " +
                             std::to_string(image_size.width) + " x " +
                             std::to_string(image_size.height) +
                             ": the aspect ratios differ too much to scale one to the other");
  cv::Mat out;
  cv::resize(mask, out, image_size, 0, 0, cv::INTER_NEAREST);
  return out;
}

std::vector<MaskedImage> pairImagesWithMasks(const std::string& images_dir,
                                             const std::string& masks_dir) {
  namespace fs = std::filesystem;
  const std::vector<std::string> images = listImages(images_dir);
  if (images.empty()) throw std::runtime_error(images_dir + ": no image in the folder");
  std::map<std::string, std::string> masks;  // stem -> path
  for (const std::string& m : listImages(masks_dir)) {
    const std::string stem = fs::path(m).stem().string();
    if (!masks.emplace(stem, m).second)
      throw std::runtime_error(masks_dir + ": two masks for " + stem + " (" + masks[stem] +
                               " and " + m + ")");
  }
  std::vector<MaskedImage> out;
  for (const std::string& im : images) {
    const auto it = masks.find(fs::path(im).stem().string());
    if (it == masks.end()) throw std::runtime_error(im + ": no mask of that name in " + masks_dir);
    out.push_back({im, it->second});
  }
  return out;
}

}  // namespace adaptive_perception::io
