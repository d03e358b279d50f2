#include "adaptive_perception/localization/image_likelihood.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "adaptive_perception/math/log_add.h"

namespace adaptive_perception::localization {

namespace {
constexpr double kLogUniformYuv = -16.635532333438686;  // log(1 / 256^3)
}  // namespace

double gridPixelCount(int w, int h, int s) {
  auto along = [s](int n) { return n > s / 2 ? (n - 1 - s / 2) / s + 1 : 0; };
  return static_cast<double>(along(w)) * along(h);
}

std::vector<world::PixelCoord> pixelGrid(const world::PinholeCamera& camera, int s, int* cols) {
  std::vector<world::PixelCoord> pixels;
  *cols = 0;
  for (int u = s / 2; u < camera.width_px; u += s) ++*cols;
  for (int v = s / 2; v < camera.height_px; v += s)
    for (int u = s / 2; u < camera.width_px; u += s)
      pixels.push_back({static_cast<std::uint16_t>(u), static_cast<std::uint16_t>(v)});
  return pixels;
}

std::vector<NeighbourOffset> neighbourOffsets(const world::PinholeCamera& camera,
                                              const std::vector<world::PixelCoord>& pixels,
                                              int stride, const Eigen::Isometry3d& base_to_optical,
                                              const ImageLikelihoodConfig& config) {
  std::vector<NeighbourOffset> out(pixels.size());
  const double tol = config.position_tolerance_m;
  if (tol <= 0.0 && config.heading_tolerance_rad <= 0.0 && config.pitch_tolerance_rad <= 0.0)
    return out;
  const Eigen::Vector3d origin = base_to_optical.translation();
  const Eigen::Isometry3d optical_from_base = base_to_optical.inverse();
  // A heading error turns the whole view: about fx * heading_tolerance pixels sideways.
  const double heading_px = camera.fx_px * config.heading_tolerance_rad;
  // A pitch error of the camera (a legged robot's body sways) moves the whole view up or down.
  const double pitch_px = camera.fy_px * config.pitch_tolerance_rad;
  auto cells = [&](double px) {
    return static_cast<std::uint8_t>(
        std::min<double>(config.max_neighbourhood_cells, std::floor(px / stride + 0.5)));
  };
  for (size_t j = 0; j < pixels.size(); ++j) {
    const Eigen::Vector3d ray =
        base_to_optical.linear() * camera.rayThrough(pixels[j].u, pixels[j].v);
    double du = 0.0, dv = 0.0;
    if (ray.z() < -1e-9 && origin.z() > 0.0) {
      // The ground point this pixel sees, and where the ground points tol away along x and y
      // land in the image.
      const Eigen::Vector3d ground = origin + (-origin.z() / ray.z()) * ray;
      Eigen::Vector2d at;
      if (camera.project(optical_from_base * ground, &at)) {
        for (const Eigen::Vector3d& step :
             {Eigen::Vector3d(tol, 0, 0), Eigen::Vector3d(-tol, 0, 0), Eigen::Vector3d(0, tol, 0),
              Eigen::Vector3d(0, -tol, 0)}) {
          Eigen::Vector2d moved;
          if (!camera.project(optical_from_base * (ground + step), &moved)) continue;
          du = std::max(du, std::fabs(moved.x() - at.x()));
          dv = std::max(dv, std::fabs(moved.y() - at.y()));
        }
      }
    } else {
      // Above the horizon (walls, goals, beacons): taken as 2 m away, a sideways shift only.
      du = camera.fx_px * tol / 2.0;
    }
    out[j].du = cells(du + heading_px);
    out[j].dv = cells(dv + pitch_px);
  }
  return out;
}

ImageLikelihood::ImageLikelihood(const world::FieldMap& map, const world::PinholeCamera& camera,
                                 const color::ColorModelConfig& model,
                                 const ImageLikelihoodConfig& config)
    : renderer_(map, camera), model_(model), config_(config) {
  config_.validate();
}

SampledImage ImageLikelihood::grid(int stride) const {
  SampledImage image;
  image.stride = stride;
  image.pixels = pixelGrid(camera(), stride, &image.cols);
  return image;
}

BackgroundDensity::BackgroundDensity(const cv::Mat& yuv, const cv::Mat& mask,
                                     double uniform_weight) {
  if (yuv.type() != CV_8UC3 || mask.type() != CV_8UC1 || mask.size() != yuv.size())
    throw std::invalid_argument(
        "BackgroundDensity: needs a YUV image (CV_8UC3) and a mask "
        "(CV_8UC1) of one size");
  if (!(uniform_weight > 0.0 && uniform_weight <= 1.0))
    throw std::invalid_argument("BackgroundDensity: uniform_weight must be in (0, 1]");
  constexpr int kBins = 256 / kBinLevels;
  std::vector<double> count(kBins * kBins * kBins, 0.0);
  double total = 0.0;
  for (int r = 0; r < yuv.rows; ++r) {
    const cv::Vec3b* p = yuv.ptr<cv::Vec3b>(r);
    const std::uint8_t* m = mask.ptr<std::uint8_t>(r);
    for (int c = 0; c < yuv.cols; ++c) {
      if (!m[c]) continue;
      count[(p[c][0] / kBinLevels * kBins + p[c][1] / kBinLevels) * kBins + p[c][2] / kBinLevels] +=
          1.0;
      total += 1.0;
    }
  }
  if (total < kMinPixels) return;
  const double uniform = std::exp(kLogUniformYuv);
  const double bin_volume = static_cast<double>(kBinLevels) * kBinLevels * kBinLevels;
  log_density_.resize(count.size());
  for (std::size_t b = 0; b < count.size(); ++b)
    log_density_[b] = static_cast<float>(std::log(
        uniform_weight * uniform + (1.0 - uniform_weight) * count[b] / (total * bin_volume)));
}

double BackgroundDensity::logDensity(const Eigen::Vector3d& yuv) const {
  if (log_density_.empty()) return kLogUniformYuv;
  constexpr int kBins = 256 / kBinLevels;
  const auto bin = [](double v) {
    return std::clamp(static_cast<int>(v) / kBinLevels, 0, kBins - 1);
  };
  return log_density_[(bin(yuv[0]) * kBins + bin(yuv[1])) * kBins + bin(yuv[2])];
}

void ImageLikelihood::setColours(const cv::Mat& yuv, SampledImage* image,
                                 const BackgroundDensity* background) const {
  const world::PinholeCamera& cam = camera();
  if (yuv.type() != CV_8UC3 || yuv.cols != cam.width_px || yuv.rows != cam.height_px)
    throw std::invalid_argument("image likelihood: expected a " + std::to_string(cam.width_px) +
                                "x" + std::to_string(cam.height_px) + " YUV image (CV_8UC3), got " +
                                std::to_string(yuv.cols) + "x" + std::to_string(yuv.rows) +
                                " of type " + std::to_string(yuv.type()));
  image->values.resize(image->pixels.size());
  for (size_t j = 0; j < image->pixels.size(); ++j) {
    const cv::Vec3b c = yuv.at<cv::Vec3b>(image->pixels[j].v, image->pixels[j].u);
    image->values[j] = Eigen::Vector3d(c[0], c[1], c[2]);
  }
  image->background_log_density.clear();
  if (background) {
    image->background_log_density.resize(image->values.size());
    for (size_t j = 0; j < image->values.size(); ++j)
      image->background_log_density[j] = background->logDensity(image->values[j]);
  }
}

void ImageLikelihood::setOffsets(const Eigen::Isometry3d& base_to_optical,
                                 SampledImage* image) const {
  image->offsets =
      neighbourOffsets(camera(), image->pixels, image->stride, base_to_optical, config_);
}

SampledImage ImageLikelihood::sample(const cv::Mat& yuv, int stride,
                                     const Eigen::Isometry3d& base_to_optical,
                                     const BackgroundDensity* background) const {
  SampledImage image = grid(stride);
  setColours(yuv, &image, background);
  setOffsets(base_to_optical, &image);
  return image;
}

double ImageLikelihood::logLikelihood(const SampledImage& image, const math::SE2& pose,
                                      const color::SwitchingColorFilter& lighting,
                                      const Eigen::Isometry3d& base_to_optical,
                                      color::ColorObservation* obs_out, int* used_out) const {
  const std::vector<world::PixelCoord>& pixels = image.pixels;
  const std::vector<NeighbourOffset>& offsets = image.offsets;
  const std::vector<Eigen::Vector3d>& pixel_yuv = image.values;
  const int grid_cols = image.cols;
  const Eigen::Isometry3d cam = world::planarToIsometry(pose) * base_to_optical;
  std::vector<std::uint8_t> labels;
  renderer_.renderPixels(cam, pixels, &labels);
  const int cols = grid_cols, rows = static_cast<int>(pixels.size()) / std::max(grid_cols, 1);
  // Eq. (9) under the predicted lighting, in a mixture with the uniform density; eq. (16) is the
  // (tempered) product over the pixels. With several lighting modes the image likelihood is the
  // mixture over the modes with their predicted probabilities (the mode is part of the lighting
  // state).
  const color::ColorModelConfig& mc = model_;
  const double log_in = std::log1p(-config_.outlier_probability);
  const double log_out = config_.outlier_probability > 0.0
                             ? std::log(config_.outlier_probability) + kLogUniformYuv
                             : -std::numeric_limits<double>::infinity();
  std::int8_t slot[256];
  std::fill(std::begin(slot), std::end(slot), static_cast<std::int8_t>(-1));
  for (int k = 0; k < mc.numColors(); ++k) slot[mc.classes[k]] = static_cast<std::int8_t>(k);
  const std::vector<double> mode_p = lighting.predictedModeProbabilities();
  const int modes = lighting.numModes(), colours = mc.numColors();
  std::vector<double> mode_ll(modes, 0.0);
  // Eq. (9) per (mode, colour), flattened for the pixel loop: log(1 - outlier) + the Gaussian's
  // log normaliser, its mean and the symmetric inverse covariance (each off-diagonal pair summed).
  struct Gauss {
    double log_scale, m0, m1, m2, a00, a01, a02, a11, a12, a22;
  };
  std::vector<Gauss> gauss(static_cast<size_t>(modes) * colours);
  for (int m = 0; m < modes; ++m) {
    const color::PixelClassifier cls = lighting.mode(m).classifier();
    for (int k = 0; k < colours; ++k) {
      const Eigen::Vector3d& mu = cls.means()[k];
      const Eigen::Matrix3d& a = cls.inverseCovs()[k];
      gauss[static_cast<size_t>(m) * colours + k] = {log_in + cls.logNorm(k),
                                                     mu.x(),
                                                     mu.y(),
                                                     mu.z(),
                                                     a(0, 0),
                                                     a(0, 1) + a(1, 0),
                                                     a(0, 2) + a(2, 0),
                                                     a(1, 1),
                                                     a(1, 2) + a(2, 1),
                                                     a(2, 2)};
    }
  }
  int used = 0;
  color::ColorObservation obs;
  obs.counts.assign(mc.numColors(), 0);
  obs.means.assign(mc.numColors(), Eigen::Vector3d::Zero());
  obs.variances.assign(mc.numColors(), Eigen::Vector3d::Zero());
  // A pixel's predicted colour is a distribution: half the colour predicted at it, an eighth each
  // the colours at the grid pixels its offsets away (a prediction blurred by the pose
  // tolerance); its likelihood is the mixture over them, background scoring the uniform density.
  // Being a proper mixture it does not favour poses that predict busier views.
  // log of a candidate's share, in eighths (1/2 + n/8).
  static const std::array<double, 9> kLogEighths = [] {
    std::array<double, 9> t{};
    for (int e = 1; e <= 8; ++e) t[e] = std::log(e / 8.0);
    return t;
  }();
  const bool own_background = !image.background_log_density.empty();
  for (size_t j = 0; j < pixels.size(); ++j) {
    const Eigen::Vector3d& yuv = pixel_yuv[j];
    // Background (or an unmodelled colour): the uniform density, or the image's own
    // background's. Every pixel must contribute, or poses that see more background would
    // score higher for having fewer terms.
    const double background = own_background ? image.background_log_density[j] : kLogUniformYuv;
    const auto pixelLogLikelihood = [&](int m, int k) {
      if (k < 0) return background;
      const Gauss& g = gauss[static_cast<size_t>(m) * colours + k];
      const double d0 = yuv.x() - g.m0, d1 = yuv.y() - g.m1, d2 = yuv.z() - g.m2;
      const double q = d0 * (g.a00 * d0 + g.a01 * d1 + g.a02 * d2) +
                       d1 * (g.a11 * d1 + g.a12 * d2) + g.a22 * d2 * d2;
      return math::logAddExp(g.log_scale - 0.5 * q, log_out);
    };
    std::uint8_t cand[5];
    int eighths[5];
    int nc = 0;
    cand[nc] = labels[j];
    eighths[nc++] = 8;
    const NeighbourOffset d = offsets[j];
    if (d.du > 0 || d.dv > 0) {
      eighths[0] = 4;
      const int r = static_cast<int>(j) / cols, c = static_cast<int>(j) % cols;
      const int around[4] = {
          r * cols + std::max(c - d.du, 0), r * cols + std::min(c + d.du, cols - 1),
          std::max(r - d.dv, 0) * cols + c, std::min(r + d.dv, rows - 1) * cols + c};
      for (int n : around) {
        const int at = static_cast<int>(std::find(cand, cand + nc, labels[n]) - cand);
        if (at == nc) {
          cand[nc] = labels[n];
          eighths[nc++] = 1;
        } else {
          ++eighths[at];
        }
      }
    }
    const int k = slot[labels[j]];
    if (nc == 1) {
      // One colour all around (most pixels): no mixture.
      for (int m = 0; m < modes; ++m) mode_ll[m] += pixelLogLikelihood(m, k);
    } else {
      for (int m = 0; m < modes; ++m) {
        double ll = -std::numeric_limits<double>::infinity();
        for (int c = 0; c < nc; ++c)
          ll = math::logAddExp(ll, pixelLogLikelihood(m, slot[cand[c]]) + kLogEighths[eighths[c]]);
        mode_ll[m] += ll;
      }
    }
    if (k < 0) continue;
    ++used;
    ++obs.counts[k];
    obs.means[k] += yuv;
  }
  double best = -std::numeric_limits<double>::infinity();
  for (int m = 0; m < modes; ++m)
    best = std::max(best, std::log(std::max(mode_p[m], 1e-300)) + mode_ll[m]);
  double sum = 0.0;
  for (int m = 0; m < modes; ++m)
    sum += std::exp(std::log(std::max(mode_p[m], 1e-300)) + mode_ll[m] - best);
  const double ll = best + std::log(sum);
  for (int k = 0; k < mc.numColors(); ++k)
    if (obs.counts[k] > 0) obs.means[k] /= obs.counts[k];
  if (obs_out) *obs_out = std::move(obs);
  if (used_out) *used_out = used;
  return config_.exponent * ll;
}

}  // namespace adaptive_perception::localization
