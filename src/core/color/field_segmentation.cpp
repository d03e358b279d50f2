#include "adaptive_perception/color/field_segmentation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::color {

const config::Fields<FieldSegmentationConfig>& FieldSegmentationConfig::fields() {
  using C = FieldSegmentationConfig;
  using config::closed;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("seed_region_share", &C::seed_region_share, config::aboveZero(1),
               "share of the image height, from the bottom, where the carpet's chroma is sought")
          .add("seed_luma_share", &C::seed_luma_share, config::aboveZero(1),
               "the carpet's seed keeps this central share of its pixels' luma")
          .add("em_iterations", &C::em_iterations, closed(0, 100),
               "EM iterations of the colour mixture (carpet, line paint, other)")
          .add("em_stride_px", &C::em_stride_px, closed(1, 64),
               "EM uses every n-th pixel in both directions (px)")
          .add("prior_std", &C::prior_std, config::aboveZero(1000),
               "prior spread of each class mean around its seed (8-bit levels)")
          .add("boundary_line_weight", &C::boundary_line_weight, closed(-1, 1),
               "weight of a line-paint pixel in the boundary's running sum (carpet +1, other -1)")
          .add("boundary_other_weight", &C::boundary_other_weight, closed(0, 100),
               "weight of a pixel of neither carpet nor paint in the boundary's running sum")
          .add("boundary_step_cost", &C::boundary_step_cost, closed(0, 1000),
               "cost of a one-row step of the boundary between neighbouring columns (px)")
          .add("boundary_min_width_share", &C::boundary_min_width_share, closed(0, 1),
               "narrower peaks of the boundary are removed, as a share of the image width")
          .add("boundary_convex", &C::boundary_convex,
               "replace the boundary by its upper convex hull")
          .add("line_window_share", &C::line_window_share, config::aboveZero(0.5),
               "top-hat window for the lines, as a share of the image width")
          .add("line_blur_px", &C::line_blur_px, closed(0, 20),
               "the luma is smoothed with a Gaussian of this standard deviation before the top-hat "
               "(px)")
          .add("line_min_area_share", &C::line_min_area_share, closed(0, 1),
               "line strokes smaller than this share of the image are grass texture")
          .add("line_min_elongation", &C::line_min_elongation, closed(0, 1000),
               "line strokes less elongated than this (length^2 / area, length 4 sd along the "
               "major axis; about 1.33 length / width for a bar) are specks or blobs, not paint")
          .add("line_object_window_share", &C::line_object_window_share, config::aboveZero(0.5),
               "window about a line pixel where objects on the field are counted, as a share of "
               "the image width")
          .add("line_max_object_share", &C::line_max_object_share, closed(0, 1),
               "a line pixel has at most this share of object pixels (dark_chroma_sigma) among "
               "the field's pixels of its window; 1 = off")
          .add("dark_chroma_sigma", &C::dark_chroma_sigma, config::aboveZero(100),
               "a pixel darker than the carpet and more than this many of the carpet's chroma "
               "standard deviations (Mahalanobis) from its chroma is an object on the field")
          .add("line_contrast_sigma", &C::line_contrast_sigma, closed(0, 100),
               "a line pixel stands this many carpet luma standard deviations above its "
               "surroundings");
  return f;
}

void FieldSegmentationConfig::validate() const { fields().validate(*this); }

namespace {

constexpr int kCarpet = 0, kPaint = 1, kOther = 2, kDark = 3, kClasses = 4;

struct Gauss {
  Eigen::Vector3d mean;
  Eigen::Matrix3d cov;
  Eigen::Matrix3d inv;
  double log_norm = 0.0;
  double weight = 1.0 / kClasses;
  void finish() {
    cov = 0.5 * (cov + cov.transpose()) + 1.0 * Eigen::Matrix3d::Identity();
    inv = cov.inverse();
    log_norm = -0.5 * std::log(cov.determinant()) - 1.5 * std::log(2.0 * M_PI);
  }
  double logLik(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d d = x - mean;
    return std::log(weight) + log_norm - 0.5 * d.dot(inv * d);
  }
};

Eigen::Vector3d pixel(const cv::Mat& yuv, int r, int c) {
  const cv::Vec3b& p = yuv.at<cv::Vec3b>(r, c);
  return {double(p[0]), double(p[1]), double(p[2])};
}

// Mean and covariance of samples.
void moments(const std::vector<Eigen::Vector3d>& xs, Gauss* g) {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& x : xs) m += x;
  m /= double(xs.size());
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (const auto& x : xs) c += (x - m) * (x - m).transpose();
  g->mean = m;
  g->cov = c / double(xs.size());
}

// The carpet's seed: pixels of the most common green chroma in the lower part of the image.
bool seedCarpet(const cv::Mat& yuv, const FieldSegmentationConfig& cfg, Gauss* carpet) {
  constexpr int kBins = 32, kShift = 3;  // 8 levels per chroma bin
  std::vector<int> hist(kBins * kBins, 0);
  const int r0 = static_cast<int>(std::floor(yuv.rows * (1.0 - cfg.seed_region_share)));
  for (int r = r0; r < yuv.rows; r += cfg.em_stride_px)
    for (int c = 0; c < yuv.cols; c += cfg.em_stride_px) {
      const cv::Vec3b& p = yuv.at<cv::Vec3b>(r, c);
      ++hist[(p[1] >> kShift) * kBins + (p[2] >> kShift)];
    }
  int best = -1, best_count = 0;
  for (int u = 1; u < kBins / 2; ++u)  // green: Cb < 128 and Cr < 128
    for (int v = 1; v < kBins / 2; ++v) {
      int n = 0;
      for (int du = -1; du <= 1; ++du)
        for (int dv = -1; dv <= 1; ++dv) n += hist[(u + du) * kBins + v + dv];
      if (n > best_count) best_count = n, best = u * kBins + v;
    }
  if (best < 0 || best_count < 20) return false;
  const int bu = best / kBins, bv = best % kBins;
  std::vector<Eigen::Vector3d> xs;
  for (int r = r0; r < yuv.rows; r += cfg.em_stride_px)
    for (int c = 0; c < yuv.cols; c += cfg.em_stride_px) {
      const cv::Vec3b& p = yuv.at<cv::Vec3b>(r, c);
      if (std::abs((p[1] >> kShift) - bu) <= 1 && std::abs((p[2] >> kShift) - bv) <= 1)
        xs.push_back({double(p[0]), double(p[1]), double(p[2])});
    }
  {
    // The central seed_luma_share of their luma: a wall or a floor of the carpet's chroma in the
    // seed region must not widen the carpet's class (an interquartile estimate by default).
    const double keep = cfg.seed_luma_share;
    std::vector<double> ys;
    for (const auto& x : xs) ys.push_back(x[0]);
    std::sort(ys.begin(), ys.end());
    const double lo = ys[static_cast<size_t>((0.5 - keep / 2) * (ys.size() - 1))];
    const double hi = ys[static_cast<size_t>((0.5 + keep / 2) * (ys.size() - 1))];
    std::vector<Eigen::Vector3d> kept;
    for (const auto& x : xs)
      if (x[0] >= lo && x[0] <= hi) kept.push_back(x);
    xs.swap(kept);
  }
  moments(xs, carpet);
  return true;
}

}  // namespace

FieldSegmentation segmentField(const cv::Mat& bgr, const FieldSegmentationConfig& cfg) {
  if (bgr.empty() || bgr.type() != CV_8UC3)
    throw std::invalid_argument("segmentField: expected a non-empty BGR8 (CV_8UC3) image");
  cv::Mat yuv;
  cv::cvtColor(bgr, yuv, cv::COLOR_BGR2YCrCb);  // channels Y, Cr, Cb: swapped to Y, U, V below
  cv::Mat planes[3];
  cv::split(yuv, planes);
  std::swap(planes[1], planes[2]);
  cv::merge(planes, 3, yuv);
  return segmentFieldYuv(yuv, cfg);
}

FieldSegmentation segmentFieldYuv(const cv::Mat& yuv, const FieldSegmentationConfig& cfg) {
  cfg.validate();
  if (yuv.empty() || yuv.type() != CV_8UC3)
    throw std::invalid_argument("segmentFieldYuv: expected a non-empty YUV (CV_8UC3) image");
  const int rows = yuv.rows, cols = yuv.cols;

  FieldSegmentation out;
  out.labels = cv::Mat(rows, cols, CV_8UC1, cv::Scalar(world::kBackground));
  out.boundary_row = cv::Mat(1, cols, CV_32SC1, cv::Scalar(rows));

  // 1. Seeds.
  std::array<Gauss, kClasses> g;
  if (!seedCarpet(yuv, cfg, &g[kCarpet])) return out;  // no green at all: no field
  std::vector<Eigen::Vector3d> sample;
  for (int r = 0; r < rows; r += cfg.em_stride_px)
    for (int c = 0; c < cols; c += cfg.em_stride_px) sample.push_back(pixel(yuv, r, c));
  moments(sample, &g[kOther]);
  g[kPaint].mean = {0.5 * (255.0 + g[kCarpet].mean[0]), 128.0, 128.0};
  g[kPaint].cov = Eigen::Vector3d(400.0, 64.0, 64.0).asDiagonal();
  {
    std::vector<double> ys;
    for (const auto& x : sample) ys.push_back(x[0]);
    std::nth_element(ys.begin(), ys.begin() + ys.size() / 20, ys.end());
    g[kDark].mean = {ys[ys.size() / 20], 128.0, 128.0};
    g[kDark].cov = Eigen::Vector3d(100.0, 16.0, 16.0).asDiagonal();
  }
  std::array<Eigen::Vector3d, kClasses> seed;
  for (int k = 0; k < kClasses; ++k) g[k].finish(), seed[k] = g[k].mean;

  // 2. EM with each class mean pulled towards its seed.
  std::vector<std::array<double, kClasses>> resp(sample.size());
  for (int it = 0; it < cfg.em_iterations; ++it) {
    for (size_t i = 0; i < sample.size(); ++i) {
      std::array<double, kClasses> l;
      double mx = -1e300;
      for (int k = 0; k < kClasses; ++k) mx = std::max(mx, l[k] = g[k].logLik(sample[i]));
      double s = 0.0;
      for (int k = 0; k < kClasses; ++k) s += (l[k] = std::exp(l[k] - mx));
      for (int k = 0; k < kClasses; ++k) resp[i][k] = l[k] / s;
    }
    for (int k = 0; k < kClasses; ++k) {
      double n = 0.0;
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (size_t i = 0; i < sample.size(); ++i) n += resp[i][k], sum += resp[i][k] * sample[i];
      if (n < 10.0) continue;  // a class the image does not show keeps its seed
      Eigen::Vector3d mean;
      for (int ch = 0; ch < 3; ++ch) {
        const double pull = g[k].cov(ch, ch) / (cfg.prior_std * cfg.prior_std);
        mean[ch] = (k >= kOther) ? sum[ch] / n : (sum[ch] + pull * seed[k][ch]) / (n + pull);
      }
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (size_t i = 0; i < sample.size(); ++i)
        cov += resp[i][k] * (sample[i] - mean) * (sample[i] - mean).transpose();
      g[k].mean = mean;
      g[k].cov = cov / n;
      g[k].weight = std::max(n / double(sample.size()), 1e-3);
      g[k].finish();
    }
  }
  out.carpet_mean_yuv = {g[kCarpet].mean[0], g[kCarpet].mean[1], g[kCarpet].mean[2]};
  out.line_mean_yuv = {g[kPaint].mean[0], g[kPaint].mean[1], g[kPaint].mean[2]};

  // Every pixel's class.
  cv::Mat cls(rows, cols, CV_8UC1);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const Eigen::Vector3d x = pixel(yuv, r, c);
      int best = 0;
      double bl = g[0].logLik(x);
      for (int k = 1; k < kClasses; ++k) {
        const double l = g[k].logLik(x);
        if (l > bl) bl = l, best = k;
      }
      cls.at<std::uint8_t>(r, c) = static_cast<std::uint8_t>(std::min(best, kOther));
    }

  // 3. The boundary: b_c maximising sum_c [S_c(b_c) - lambda |b_c - b_(c-1)|], S_c(b) the running
  // sum from the bottom of column c up to row b (+1 carpet, boundary_line_weight paint, -1 other);
  // b_c = rows: no field in the column. Dynamic programming over the columns, the L1 step by the
  // two-pass distance transform.
  const int states = rows + 1;
  std::vector<float> score(states), prev(states), run(states);
  std::vector<int> from(static_cast<size_t>(states) * cols), arg(states);
  // An occluder joined to the image's bottom (the robot's own arm or feet) does not cancel the
  // carpet above it: until carpet first leads, the sum restarts at zero wherever it falls below.
  for (int c = 0; c < cols; ++c) {
    double s = 0.0;
    bool bottom = true;  // still in what covers the image's bottom row (the robot's own body)
    run[rows] = 0.0f;
    for (int r = rows - 1; r >= 0; --r) {
      const int k = cls.at<std::uint8_t>(r, c);
      if (bottom) s = std::max(s, 0.0);
      if (s > 0.0) bottom = false;
      s += k == kCarpet ? 1.0 : k == kPaint ? cfg.boundary_line_weight : -cfg.boundary_other_weight;
      run[r] = static_cast<float>(s);
    }
    if (c == 0) {
      score = run;
      continue;
    }
    // best predecessor of each b: max_b' prev[b'] - lambda |b - b'|
    const float lambda = static_cast<float>(cfg.boundary_step_cost);
    std::vector<float> best(prev.begin(), prev.end());
    for (int b = 0; b < states; ++b) arg[b] = b;
    for (int b = 1; b < states; ++b)
      if (best[b - 1] - lambda > best[b]) best[b] = best[b - 1] - lambda, arg[b] = arg[b - 1];
    for (int b = states - 2; b >= 0; --b)
      if (best[b + 1] - lambda > best[b]) best[b] = best[b + 1] - lambda, arg[b] = arg[b + 1];
    for (int b = 0; b < states; ++b) {
      score[b] = run[b] + best[b];
      from[static_cast<size_t>(c) * states + b] = arg[b];
    }
    std::swap(score, prev);
    score = prev;
  }
  std::vector<int> b(cols, rows);
  b[cols - 1] = static_cast<int>(std::max_element(score.begin(), score.end()) - score.begin());
  for (int c = cols - 1; c > 0; --c) b[c - 1] = from[static_cast<size_t>(c) * states + b[c]];
  // A peak narrower than boundary_min_width_share of the image is something field-coloured above
  // the field (a green wall, grass seen through a goal's net): a grey closing of b (max, then min,
  // over the window) removes it before the hull could be drawn to it.
  {
    const int half = static_cast<int>(std::lround(0.5 * cfg.boundary_min_width_share * cols));
    auto slide = [&](const std::vector<int>& in, bool take_max) {
      std::vector<int> o(in.size());
      for (int c = 0; c < cols; ++c) {
        int v = in[c];
        for (int d = std::max(0, c - half); d <= std::min(cols - 1, c + half); ++d)
          v = take_max ? std::max(v, in[d]) : std::min(v, in[d]);
        o[c] = v;
      }
      return o;
    };
    if (half > 0) b = slide(slide(b, true), false);
    // At the image's sides the window is cut off: a peak against a side survives the closing when
    // it is wider than half the window (the dark interior of a backlit hall at an image's edge,
    // taken for carpet up to the image's top). Its outer flank is out of view, so its width cannot
    // tell it from a strip of real field between a player and the side; its height can. A strip
    // within one window of a side that rises above the boundary everywhere else (the other side's
    // strip included: a robot near the camera may hide every column between) by more than the
    // window's width, so more steeply than 45 degrees, is held down to the highest row there.
    const int side = 2 * half;
    if (half > 0 && cols > 2 * side) {
      auto highest = [&](int from, int to) {
        return from < to ? *std::min_element(b.begin() + from, b.begin() + to) : rows;
      };
      const int left_peak = highest(0, side), right_peak = highest(cols - side, cols);
      const int left_top = highest(side, cols), right_top = highest(0, cols - side);
      auto hold = [&](int from, int to, int peak, int top) {
        if (top < rows && top - peak > side)
          for (int c = from; c < to; ++c) b[c] = std::max(b[c], top);
      };
      hold(0, side, left_peak, left_top);
      hold(cols - side, cols, right_peak, right_top);
    }
  }
  std::vector<int> boundary = b;
  if (cfg.boundary_convex) {
    // Upper convex hull (the greatest convex minorant of b in image coordinates, y down).
    std::vector<int> hull;
    for (int c = 0; c < cols; ++c) {
      if (b[c] >= rows) continue;
      while (hull.size() >= 2) {
        const int o = hull[hull.size() - 2], a = hull.back();
        const double cross =
            double(a - o) * double(b[c] - b[o]) - double(b[a] - b[o]) * double(c - o);
        if (cross <= 0.0)
          hull.pop_back();  // a lies below the chord o -> c: not on the hull
        else
          break;
      }
      hull.push_back(c);
    }
    for (size_t i = 0; i + 1 < hull.size(); ++i)
      for (int c = hull[i] + 1; c < hull[i + 1]; ++c) {
        const double t = double(c - hull[i]) / double(hull[i + 1] - hull[i]);
        boundary[c] = static_cast<int>(std::lround(b[hull[i]] + t * (b[hull[i + 1]] - b[hull[i]])));
      }
  }
  for (int c = 0; c < cols; ++c) out.boundary_row.at<int>(0, c) = boundary[c];

  // 4. Lines: thin bright paint inside the field.
  cv::Mat y;
  cv::extractChannel(yuv, y, 0);
  int win = std::max(3, static_cast<int>(std::lround(cfg.line_window_share * cols)) | 1);
  if (cfg.line_blur_px > 0.0) cv::GaussianBlur(y, y, {0, 0}, cfg.line_blur_px);
  cv::Mat tophat;
  cv::morphologyEx(y, tophat, cv::MORPH_TOPHAT,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, {win, win}));
  const double carpet_chroma = std::hypot(g[kCarpet].mean[1] - 128.0, g[kCarpet].mean[2] - 128.0);
  // Paler than the carpet: chroma over luma, since a tinted light gives white paint a chroma
  // that grows with its brightness (warm light: paint brighter and more chromatic than the grass).
  const double carpet_pale = carpet_chroma / std::max(1.0, g[kCarpet].mean[0]);
  auto pale = [&](const cv::Vec3b& p) {
    return std::hypot(p[1] - 128.0, p[2] - 128.0) <= carpet_pale * std::max<double>(1.0, p[0]);
  };
  const double min_contrast = cfg.line_contrast_sigma * std::sqrt(g[kCarpet].cov(0, 0));
  // Objects on the field (below the boundary, darker than the carpet and of another chroma: a
  // robot's joints, the ball's patches, a leg) and the field's pixels, counted over a window about
  // each pixel.
  cv::Mat object_count, field_count;
  {
    const Eigen::Matrix2d chroma_inv = g[kCarpet].cov.bottomRightCorner<2, 2>().inverse();
    const double dark_m2 = cfg.dark_chroma_sigma * cfg.dark_chroma_sigma;
    auto chromaM2 = [&](const cv::Vec3b& q) {
      const Eigen::Vector2d d(q[1] - g[kCarpet].mean[1], q[2] - g[kCarpet].mean[2]);
      return d.dot(chroma_inv * d);
    };
    cv::Mat object(rows, cols, CV_32F, cv::Scalar(0)), field(rows, cols, CV_32F, cv::Scalar(0));
    for (int c = 0; c < cols; ++c)
      for (int r = boundary[c]; r < rows; ++r) {
        field.at<float>(r, c) = 1.0f;
        const cv::Vec3b& q = yuv.at<cv::Vec3b>(r, c);
        if (q[0] < g[kCarpet].mean[0] && chromaM2(q) > dark_m2) object.at<float>(r, c) = 1.0f;
      }
    const int ow =
        std::max(3, static_cast<int>(std::lround(cfg.line_object_window_share * cols)) | 1);
    cv::boxFilter(object, object_count, CV_32F, {ow, ow}, {-1, -1}, false);
    cv::boxFilter(field, field_count, CV_32F, {ow, ow}, {-1, -1}, false);
  }
  for (int c = 0; c < cols; ++c)
    for (int r = boundary[c]; r < rows; ++r) {
      const cv::Vec3b& p = yuv.at<cv::Vec3b>(r, c);
      const bool on_carpet = object_count.at<float>(r, c) <=
                             cfg.line_max_object_share * field_count.at<float>(r, c);
      const bool line = pale(p) && on_carpet && tophat.at<std::uint8_t>(r, c) >= min_contrast;
      out.labels.at<std::uint8_t>(r, c) = line ? world::kWhite : world::kGreen;
    }
  // Grass texture leaves specks; a painted line is a long, narrow stroke.
  const cv::Mat lines = out.labels == world::kWhite;
  cv::Mat comp, stats, centroids;
  const int n = cv::connectedComponentsWithStats(lines, comp, stats, centroids, 8, CV_32S);
  // Second moments of each stroke about its centroid.
  std::vector<Eigen::Vector3d> moments(n, Eigen::Vector3d::Zero());  // xx, yy, xy
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int id = comp.at<int>(r, c);
      if (id <= 0) continue;
      const double dx = c - centroids.at<double>(id, 0), dy = r - centroids.at<double>(id, 1);
      moments[id] += Eigen::Vector3d(dx * dx, dy * dy, dx * dy);
    }
  const double min_area = cfg.line_min_area_share * rows * cols;
  std::vector<char> drop(n, 0);
  for (int id = 1; id < n; ++id) {
    const double area = stats.at<int>(id, cv::CC_STAT_AREA);
    const Eigen::Vector3d m = moments[id] / area;
    // The larger eigenvalue of the covariance [[xx, xy], [xy, yy]].
    const double major_var =
        0.5 * (m[0] + m[1]) + std::sqrt(0.25 * (m[0] - m[1]) * (m[0] - m[1]) + m[2] * m[2]);
    const double length = 4.0 * std::sqrt(major_var);
    drop[id] = area < min_area || length * length < cfg.line_min_elongation * area;
  }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int id = comp.at<int>(r, c);
      if (id > 0 && id < n && drop[id]) out.labels.at<std::uint8_t>(r, c) = world::kGreen;
    }
  return out;
}

}  // namespace adaptive_perception::color
