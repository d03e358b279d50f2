#include "adaptive_perception/color/color_space.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::color {

namespace {
inline std::uint8_t clip8(float x) {
  return static_cast<std::uint8_t>(x <= 0.f ? 0 : (x >= 255.f ? 255 : std::lround(x)));
}
}  // namespace

cv::Mat packUyvy(const cv::Mat& y, const cv::Mat& u, const cv::Mat& v) {
  if (y.type() != CV_32F || u.type() != CV_32F || v.type() != CV_32F || y.size() != u.size() ||
      y.size() != v.size()) {
    throw std::invalid_argument("packUyvy: expects three CV_32F planes of one size");
  }
  if (y.cols % 2 != 0) throw std::invalid_argument("packUyvy: UYVY needs an even image width");
  cv::Mat out(y.rows, y.cols, CV_8UC2);
  for (int r = 0; r < y.rows; ++r) {
    const float* py = y.ptr<float>(r);
    const float* pu = u.ptr<float>(r);
    const float* pv = v.ptr<float>(r);
    std::uint8_t* o = out.ptr<std::uint8_t>(r);
    for (int c = 0; c < y.cols; c += 2) {
      o[2 * c + 0] = clip8(0.5f * (pu[c] + pu[c + 1]));
      o[2 * c + 1] = clip8(py[c]);
      o[2 * c + 2] = clip8(0.5f * (pv[c] + pv[c + 1]));
      o[2 * c + 3] = clip8(py[c + 1]);
    }
  }
  return out;
}

cv::Mat unpackUyvy(const cv::Mat& uyvy) {
  if (uyvy.type() != CV_8UC2 || uyvy.cols % 2 != 0)
    throw std::invalid_argument("unpackUyvy: expects CV_8UC2 of even width");
  cv::Mat out(uyvy.rows, uyvy.cols, CV_8UC3);
  for (int r = 0; r < uyvy.rows; ++r) {
    const std::uint8_t* s = uyvy.ptr<std::uint8_t>(r);
    std::uint8_t* o = out.ptr<std::uint8_t>(r);
    for (int c = 0; c < uyvy.cols; c += 2) {
      const std::uint8_t u = s[2 * c], y0 = s[2 * c + 1], v = s[2 * c + 2], y1 = s[2 * c + 3];
      o[3 * c + 0] = y0;
      o[3 * c + 1] = u;
      o[3 * c + 2] = v;
      o[3 * c + 3] = y1;
      o[3 * c + 4] = u;
      o[3 * c + 5] = v;
    }
  }
  return out;
}

cv::Mat bgrToYuv(const cv::Mat& bgr) {
  if (bgr.type() != CV_8UC3) throw std::invalid_argument("bgrToYuv: expects BGR8 (CV_8UC3)");
  cv::Mat out(bgr.rows, bgr.cols, CV_8UC3);
  for (int r = 0; r < bgr.rows; ++r) {
    const std::uint8_t* s = bgr.ptr<std::uint8_t>(r);
    std::uint8_t* o = out.ptr<std::uint8_t>(r);
    for (int c = 0; c < bgr.cols; ++c) {
      const Eigen::Vector3d yuv =
          rgbToYuv({double(s[3 * c + 2]), double(s[3 * c + 1]), double(s[3 * c])});
      for (int k = 0; k < 3; ++k)
        o[3 * c + k] = static_cast<std::uint8_t>(std::clamp(std::lround(yuv[k]), 0L, 255L));
    }
  }
  return out;
}

cv::Mat yuvToBgr(const cv::Mat& yuv) {
  if (yuv.type() != CV_8UC3) throw std::invalid_argument("yuvToBgr: expects CV_8UC3 (Y, U, V)");
  cv::Mat bgr(yuv.rows, yuv.cols, CV_8UC3);
  for (int r = 0; r < yuv.rows; ++r) {
    const std::uint8_t* s = yuv.ptr<std::uint8_t>(r);
    std::uint8_t* o = bgr.ptr<std::uint8_t>(r);
    for (int c = 0; c < yuv.cols; ++c) {
      const Eigen::Vector3d rgb =
          yuvToRgb({double(s[3 * c]), double(s[3 * c + 1]), double(s[3 * c + 2])});
      o[3 * c + 0] = clip8(static_cast<float>(rgb[2]));
      o[3 * c + 1] = clip8(static_cast<float>(rgb[1]));
      o[3 * c + 2] = clip8(static_cast<float>(rgb[0]));
    }
  }
  return bgr;
}

cv::Mat colorizeLabels(const cv::Mat& labels) {
  if (labels.type() != CV_8UC1)
    throw std::invalid_argument("colorizeLabels: expects CV_8UC1 class ids");
  cv::Mat out(labels.size(), CV_8UC3);
  for (int r = 0; r < labels.rows; ++r) {
    const std::uint8_t* s = labels.ptr<std::uint8_t>(r);
    cv::Vec3b* o = out.ptr<cv::Vec3b>(r);
    for (int c = 0; c < labels.cols; ++c) {
      const auto bgr = world::colorClassDisplayBgr(s[c]);
      o[c] = cv::Vec3b(bgr[0], bgr[1], bgr[2]);
    }
  }
  return out;
}

// Not cv::cvtColor(COLOR_YUV2BGR_UYVY): OpenCV assumes limited-range (16..235) luma there.
cv::Mat uyvyToBgr(const cv::Mat& uyvy) { return yuvToBgr(unpackUyvy(uyvy)); }

}  // namespace adaptive_perception::color
