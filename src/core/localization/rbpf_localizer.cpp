#include "adaptive_perception/localization/rbpf_localizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/gaussian.h"
#include "adaptive_perception/math/particle_set.h"
#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::localization {

namespace {
constexpr double kLogUniformYuv = -16.635532333438686;  // log(1 / 256^3)

std::uint64_t mix(std::uint64_t a, std::uint64_t b) {
  std::uint64_t x = a * 0x9E3779B97F4A7C15ull ^ (b + 0x632BE59BD9B4E019ull + (a << 6) + (a >> 2));
  x ^= x >> 31;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 29;
  return x;
}
}  // namespace

void ImageLikelihoodConfig::validate() const {
  if (reference_width_px < 16 || reference_width_px > 10000)
    throw std::invalid_argument("reference_width_px = " + std::to_string(reference_width_px) +
                                " (allowed: 16..10000)");
  if (pixel_stride < 1 || pixel_stride > 64)
    throw std::invalid_argument("pixel_stride = " + std::to_string(pixel_stride) +
                                " (allowed: 1..64)");
  if (!(outlier_probability >= 0.0 && outlier_probability < 1.0))
    throw std::invalid_argument("outlier_probability = " + std::to_string(outlier_probability) +
                                " (allowed: 0 <= p < 1)");
  if (!(exponent > 0.0 && exponent <= 1.0))
    throw std::invalid_argument("exponent = " + std::to_string(exponent) +
                                " (allowed: 0 < e <= 1)");
  if (!(position_tolerance_m >= 0.0 && position_tolerance_m <= 1.0))
    throw std::invalid_argument("position_tolerance_m = " + std::to_string(position_tolerance_m) +
                                " (allowed: 0..1)");
  if (!(heading_tolerance_rad >= 0.0 && heading_tolerance_rad <= 0.5))
    throw std::invalid_argument("heading_tolerance_rad = " + std::to_string(heading_tolerance_rad) +
                                " (allowed: 0..0.5)");
  if (max_neighbourhood_cells < 0 || max_neighbourhood_cells > 16)
    throw std::invalid_argument("max_neighbourhood_cells = " +
                                std::to_string(max_neighbourhood_cells) + " (allowed: 0..16)");
}

color::ColorModelConfig RbpfConfig::rbpfModelConfig() {
  color::ColorModelConfig c;
  c.min_pixels_per_color = 4;
  c.observation_noise_floor_var = 25.0;
  return c;
}

void RbpfConfig::validate() const {
  if (particles < 1 || particles > 1000000)
    throw std::invalid_argument("particles = " + std::to_string(particles) +
                                " (allowed: 1..1000000)");
  if (threads < 1 || threads > 256)
    throw std::invalid_argument("threads = " + std::to_string(threads) + " (allowed: 1..256)");
  if (!(resample_ess_fraction > 0.0 && resample_ess_fraction <= 1.0))
    throw std::invalid_argument("resample_ess_fraction = " + std::to_string(resample_ess_fraction) +
                                " (allowed: 0 < f <= 1)");
  if (global_pool_size < 0 || global_pool_size > 10000000)
    throw std::invalid_argument("global_pool_size = " + std::to_string(global_pool_size) +
                                " (allowed: 0..10000000)");
  if (!(global_confirm_fraction >= 0.0 && global_confirm_fraction <= 1.0))
    throw std::invalid_argument("global_confirm_fraction = " +
                                std::to_string(global_confirm_fraction) + " (allowed: 0..1)");
  if (global_confirm_frames < 0 || global_confirm_frames > 100)
    throw std::invalid_argument("global_confirm_frames = " + std::to_string(global_confirm_frames) +
                                " (allowed: 0..100, at most global_search_frames turns it off)");
  if (global_search_frames < 1 || global_search_frames > 100)
    throw std::invalid_argument("global_search_frames = " + std::to_string(global_search_frames) +
                                " (allowed: 1..100)");
  if (global_pixel_stride < 1 || global_pixel_stride > 64)
    throw std::invalid_argument("global_pixel_stride = " + std::to_string(global_pixel_stride) +
                                " (allowed: 1..64)");
  if (!(mirror_fraction >= 0.0 && mirror_fraction <= 0.5))
    throw std::invalid_argument("mirror_fraction = " + std::to_string(mirror_fraction) +
                                " (allowed: 0..0.5)");
  if (!(mirror_relative_weight > 0.0 && mirror_relative_weight <= 1.0))
    throw std::invalid_argument("mirror_relative_weight = " +
                                std::to_string(mirror_relative_weight) + " (allowed: 0 < w <= 1)");
  if (!(min_ess_fraction >= 0.0 && min_ess_fraction <= 1.0))
    throw std::invalid_argument("min_ess_fraction = " + std::to_string(min_ess_fraction) +
                                " (allowed: 0..1)");
  if (refine_candidates < 0 || refine_candidates > 1000000)
    throw std::invalid_argument("refine_candidates = " + std::to_string(refine_candidates) +
                                " (allowed: 0..1000000)");
  if (refine_rounds < 0 || refine_rounds > 20)
    throw std::invalid_argument("refine_rounds = " + std::to_string(refine_rounds) +
                                " (allowed: 0..20)");
  if (refine_tries < 0 || refine_tries > 1000)
    throw std::invalid_argument("refine_tries = " + std::to_string(refine_tries) +
                                " (allowed: 0..1000)");
  if (!(refine_sigma_m >= 0.0 && refine_sigma_m <= 5.0))
    throw std::invalid_argument("refine_sigma_m = " + std::to_string(refine_sigma_m) +
                                " (allowed: 0..5)");
  if (!(refine_sigma_rad >= 0.0 && refine_sigma_rad <= 3.2))
    throw std::invalid_argument("refine_sigma_rad = " + std::to_string(refine_sigma_rad) +
                                " (allowed: 0..3.2)");
  if (!(relocalization_interval_s >= 0.0 && relocalization_interval_s <= 1e6))
    throw std::invalid_argument("relocalization_interval_s = " +
                                std::to_string(relocalization_interval_s) + " (allowed: 0..1e6)");
  if (relocalization_pool_size < 0 || relocalization_pool_size > 10000000)
    throw std::invalid_argument(
        "relocalization_pool_size = " + std::to_string(relocalization_pool_size) +
        " (allowed: 0..10000000)");
  if (!(relocalization_fraction > 0.0 && relocalization_fraction <= 1.0))
    throw std::invalid_argument("relocalization_fraction = " +
                                std::to_string(relocalization_fraction) + " (allowed: 0 < f <= 1)");
  if (!std::isfinite(relocalization_margin))
    throw std::invalid_argument("relocalization_margin must be finite");
  if (relocalization_refine_candidates < 0 || relocalization_refine_candidates > 1000000)
    throw std::invalid_argument(
        "relocalization_refine_candidates = " + std::to_string(relocalization_refine_candidates) +
        " (allowed: 0..1000000)");
  if (!(mirror_test_margin_nats >= 0.0 && std::isfinite(mirror_test_margin_nats)))
    throw std::invalid_argument(
        "mirror_test_margin_nats = " + std::to_string(mirror_test_margin_nats) +
        " (allowed: >= 0, 0 turns the test off)");
  if (!(mirror_test_memory_s > 0.0 && mirror_test_memory_s <= 1e6))
    throw std::invalid_argument("mirror_test_memory_s = " + std::to_string(mirror_test_memory_s) +
                                " (allowed: 0 < s <= 1e6)");
  if (!(recovery_max_fraction >= 0.0 && recovery_max_fraction <= 1.0))
    throw std::invalid_argument("recovery_max_fraction = " + std::to_string(recovery_max_fraction) +
                                " (allowed: 0..1)");
  motion.validate();
  likelihood.validate();
  model.validate();
  switching.validate();
}

// A regular grid of every s-th pixel in x and y, row-major; *cols is its width.
namespace {
/// The number of grid pixels pixelGrid gives for an image of w x h at stride s.
double gridPixelCount(int w, int h, int s) {
  auto along = [s](int n) { return n > s / 2 ? (n - 1 - s / 2) / s + 1 : 0; };
  return static_cast<double>(along(w)) * along(h);
}
}  // namespace

std::vector<world::PixelCoord> pixelGrid(const world::PinholeCamera& camera, int s, int* cols) {
  std::vector<world::PixelCoord> pixels;
  *cols = 0;
  for (int u = s / 2; u < camera.width_px; u += s) ++*cols;
  for (int v = s / 2; v < camera.height_px; v += s)
    for (int u = s / 2; u < camera.width_px; u += s)
      pixels.push_back({static_cast<std::uint16_t>(u), static_cast<std::uint16_t>(v)});
  return pixels;
}

std::vector<Eigen::Vector3d> pixelValues(const cv::Mat& yuv,
                                         const std::vector<world::PixelCoord>& pixels) {
  std::vector<Eigen::Vector3d> out(pixels.size());
  for (size_t j = 0; j < pixels.size(); ++j) {
    const cv::Vec3b c = yuv.at<cv::Vec3b>(pixels[j].v, pixels[j].u);
    out[j] = Eigen::Vector3d(c[0], c[1], c[2]);
  }
  return out;
}

std::vector<NeighbourOffset> neighbourOffsets(const world::PinholeCamera& camera,
                                              const std::vector<world::PixelCoord>& pixels,
                                              int stride, const Eigen::Isometry3d& base_to_optical,
                                              const ImageLikelihoodConfig& config) {
  std::vector<NeighbourOffset> out(pixels.size());
  const double tol = config.position_tolerance_m;
  if (tol <= 0.0 && config.heading_tolerance_rad <= 0.0) return out;
  const Eigen::Vector3d origin = base_to_optical.translation();
  const Eigen::Isometry3d optical_from_base = base_to_optical.inverse();
  // A heading error turns the whole view: about fx * heading_tolerance pixels sideways.
  const double heading_px = camera.fx_px * config.heading_tolerance_rad;
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
    out[j].dv = cells(dv);
  }
  return out;
}

RbpfConfig RbpfConfig::forCamera(const world::PinholeCamera& camera) const {
  RbpfConfig c = *this;
  const int ref_w = likelihood.reference_width_px;
  if (camera.width_px == ref_w || ref_w <= 0) return c;
  const double scale = static_cast<double>(camera.width_px) / ref_w;
  auto scaled = [scale](int stride) {
    return std::max(1, static_cast<int>(std::lround(stride * scale)));
  };
  c.likelihood.pixel_stride = scaled(likelihood.pixel_stride);
  c.global_pixel_stride = scaled(global_pixel_stride);
  // The reference: this camera's aspect at the reference width, sampled at the given stride.
  const int ref_h = std::max(1, static_cast<int>(std::lround(camera.height_px / scale)));
  const double ref_count = gridPixelCount(ref_w, ref_h, likelihood.pixel_stride);
  const double count = gridPixelCount(camera.width_px, camera.height_px, c.likelihood.pixel_stride);
  if (ref_count > 0 && count > 0) c.likelihood.exponent = likelihood.exponent * ref_count / count;
  return c;
}

RbpfLocalizer::RbpfLocalizer(const world::FieldMap& map, const world::PinholeCamera& camera,
                             const std::vector<color::LightingPrior>& priors,
                             const RbpfConfig& config)
    : map_(map),
      renderer_(map, camera),
      priors_(priors),
      config_(config.forCamera(camera)),
      rng_(config.seed),
      mirror_lighting_(priors, config.model, config.switching) {
  config.validate();
  pixels_ = pixelGrid(camera, config_.likelihood.pixel_stride, &grid_cols_);
  initUniform();
}

math::SE2 RbpfLocalizer::uniformPose(math::Rng& rng) const {
  for (int tries = 0; tries < 10000; ++tries) {
    const double x = rng.uniform(-map_.carpetHalfLength(), map_.carpetHalfLength());
    const double y = rng.uniform(-map_.carpetHalfWidth(), map_.carpetHalfWidth());
    if (map_.isFree(x, y, config_.free_space_margin_m))
      return math::SE2(x, y, rng.uniform(-math::kPi, math::kPi));
  }
  return math::SE2(0, 0, 0);
}

void RbpfLocalizer::initUniform() {
  particles_.clear();
  const color::SwitchingColorFilter lighting(priors_, config_.model, config_.switching);
  for (int i = 0; i < config_.particles; ++i)
    particles_.push_back({uniformPose(rng_), lighting, 0.0});
  weights_.assign(particles_.size(), 1.0 / particles_.size());
  have_average_ = false;
  global_pending_ = config_.global_pool_size > 0;
  pool_.clear();
  pool_ll_.clear();
  pool_frames_ = 0;
  check_pool_.clear();
  check_ll_.clear();
  check_frames_ = 0;
  seconds_since_check_ = 0.0;
  window_.clear();
  confirm_pending_ = false;
  resetMirrorTest();
}

void RbpfLocalizer::initGaussian(const math::SE2& mean, const Eigen::Matrix3d& cov) {
  particles_.clear();
  const color::SwitchingColorFilter lighting(priors_, config_.model, config_.switching);
  const math::Gaussian g(Eigen::Vector3d(mean.x_m, mean.y_m, mean.yaw_rad), cov);
  for (int i = 0; i < config_.particles; ++i) {
    const Eigen::VectorXd s = g.sample(rng_);
    particles_.push_back({math::SE2(s[0], s[1], s[2]), lighting, 0.0});
  }
  weights_.assign(particles_.size(), 1.0 / particles_.size());
  have_average_ = false;
  global_pending_ = false;
  pool_.clear();
  pool_ll_.clear();
  pool_frames_ = 0;
  check_pool_.clear();
  check_ll_.clear();
  check_frames_ = 0;
  seconds_since_check_ = 0.0;
  window_.clear();
  confirm_pending_ = false;
  resetMirrorTest();
}

double RbpfLocalizer::imageLogLikelihood(const math::SE2& pose,
                                         const color::SwitchingColorFilter& lighting,
                                         const Eigen::Isometry3d& base_to_optical,
                                         color::ColorObservation* obs_out, int* used_out) const {
  if (offsets_camera_.matrix() == base_to_optical.matrix())
    return logLikelihoodAt(pixels_, grid_cols_, offsets_, pixel_yuv_, pose, lighting,
                           base_to_optical, obs_out, used_out);
  const std::vector<NeighbourOffset> offsets =
      neighbourOffsets(renderer_.camera(), pixels_, config_.likelihood.pixel_stride,
                       base_to_optical, config_.likelihood);
  return logLikelihoodAt(pixels_, grid_cols_, offsets, pixel_yuv_, pose, lighting, base_to_optical,
                         obs_out, used_out);
}

double RbpfLocalizer::logLikelihoodAt(const std::vector<world::PixelCoord>& pixels, int grid_cols,
                                      const std::vector<NeighbourOffset>& offsets,
                                      const std::vector<Eigen::Vector3d>& pixel_yuv,
                                      const math::SE2& pose,
                                      const color::SwitchingColorFilter& lighting,
                                      const Eigen::Isometry3d& base_to_optical,
                                      color::ColorObservation* obs_out, int* used_out) const {
  const Eigen::Isometry3d cam = world::planarToIsometry(pose) * base_to_optical;
  std::vector<std::uint8_t> labels;
  renderer_.renderPixels(cam, pixels, &labels);
  const int cols = grid_cols, rows = static_cast<int>(pixels.size()) / std::max(grid_cols, 1);
  // Eq. (9) under the predicted lighting, in a mixture with the uniform density; eq. (16) is the
  // (tempered) product over the pixels. With several lighting modes the image likelihood is the
  // mixture over the modes with their predicted probabilities (the mode is part of the lighting
  // state).
  const color::ColorModelConfig& mc = config_.model;
  const double log_in = std::log1p(-config_.likelihood.outlier_probability);
  const double log_out = config_.likelihood.outlier_probability > 0.0
                             ? std::log(config_.likelihood.outlier_probability) + kLogUniformYuv
                             : -std::numeric_limits<double>::infinity();
  std::int8_t slot[256];
  std::fill(std::begin(slot), std::end(slot), static_cast<std::int8_t>(-1));
  for (int k = 0; k < mc.numColors(); ++k) slot[mc.classes[k]] = static_cast<std::int8_t>(k);
  const std::vector<double> mode_p = lighting.predictedModeProbabilities();
  std::vector<double> mode_ll(lighting.numModes(), 0.0);
  std::vector<color::PixelClassifier> cls;
  for (int j = 0; j < lighting.numModes(); ++j) cls.push_back(lighting.mode(j).classifier());
  int used = 0;
  color::ColorObservation obs;
  obs.counts.assign(mc.numColors(), 0);
  obs.means.assign(mc.numColors(), Eigen::Vector3d::Zero());
  obs.variances.assign(mc.numColors(), Eigen::Vector3d::Zero());
  // A pixel's predicted colour is a distribution: half the colour predicted at it, an eighth each
  // the colours at the grid pixels its offsets away (a prediction blurred by the pose
  // tolerance); its likelihood is the mixture over them, background scoring the uniform density.
  // Being a proper mixture it does not favour poses that predict busier views.
  std::vector<double> pixel_ll(lighting.numModes());
  for (size_t j = 0; j < pixels.size(); ++j) {
    std::uint8_t cand[5];
    double share[5];
    int nc = 0;
    cand[nc] = labels[j];
    share[nc++] = 1.0;
    const NeighbourOffset d = offsets[j];
    if (d.du > 0 || d.dv > 0) {
      share[0] = 0.5;
      const int r = static_cast<int>(j) / cols, c = static_cast<int>(j) % cols;
      const int around[4] = {
          r * cols + std::max(c - d.du, 0), r * cols + std::min(c + d.du, cols - 1),
          std::max(r - d.dv, 0) * cols + c, std::min(r + d.dv, rows - 1) * cols + c};
      for (int n : around) {
        const int at = static_cast<int>(std::find(cand, cand + nc, labels[n]) - cand);
        if (at == nc) {
          cand[nc] = labels[n];
          share[nc++] = 0.125;
        } else {
          share[at] += 0.125;
        }
      }
    }
    for (int m = 0; m < lighting.numModes(); ++m) {
      double v[5], top = -std::numeric_limits<double>::infinity();
      for (int c = 0; c < nc; ++c) {
        // Background (or an unmodelled colour): the uniform density. Every pixel must contribute,
        // or poses that see more background would score higher for having fewer terms.
        const int k = slot[cand[c]];
        v[c] = kLogUniformYuv;
        if (k >= 0) {
          const double a = log_in + cls[m].logLikelihood(pixel_yuv[j], k);
          v[c] = std::max(a, log_out) + std::log1p(std::exp(-std::fabs(a - log_out)));
        }
        if (nc > 1) v[c] += std::log(share[c]);
        top = std::max(top, v[c]);
      }
      if (nc == 1) {  // one colour all around (most pixels): no mixture
        pixel_ll[m] = v[0];
        continue;
      }
      double sum = 0.0;
      for (int c = 0; c < nc; ++c) sum += std::exp(v[c] - top);
      pixel_ll[m] = top + std::log(sum);
    }
    for (int m = 0; m < lighting.numModes(); ++m) mode_ll[m] += pixel_ll[m];
    const int k = slot[labels[j]];
    if (k < 0) continue;
    ++used;
    ++obs.counts[k];
    obs.means[k] += pixel_yuv[j];
  }
  double best = -std::numeric_limits<double>::infinity();
  for (int m = 0; m < lighting.numModes(); ++m)
    best = std::max(best, std::log(std::max(mode_p[m], 1e-300)) + mode_ll[m]);
  double sum = 0.0;
  for (int m = 0; m < lighting.numModes(); ++m)
    sum += std::exp(std::log(std::max(mode_p[m], 1e-300)) + mode_ll[m] - best);
  const double ll = best + std::log(sum);
  for (int k = 0; k < mc.numColors(); ++k)
    if (obs.counts[k] > 0) obs.means[k] /= obs.counts[k];
  if (obs_out) *obs_out = std::move(obs);
  if (used_out) *used_out = used;
  return config_.likelihood.exponent * ll;
}

void RbpfLocalizer::weighParticle(size_t i, const math::SE2& odom_delta, double dt_s,
                                  const Eigen::Isometry3d& base_to_optical,
                                  std::uint64_t frame_seed) {
  Particle& p = particles_[i];
  math::Rng rng(mix(frame_seed, i));
  p.pose = sampleMotion(p.pose, odom_delta, config_.motion, rng);
  p.lighting.predict(dt_s);
  color::ColorObservation obs;
  p.log_likelihood =
      imageLogLikelihood(p.pose, p.lighting, base_to_optical, &obs, &pixels_used_[i]);
  // Section IV-B: the particle's lighting filter takes the colour means under its own labels.
  p.lighting.update(obs);
}

void RbpfLocalizer::setImage(const cv::Mat& yuv) {
  const world::PinholeCamera& cam = renderer_.camera();
  if (yuv.type() != CV_8UC3 || yuv.cols != cam.width_px || yuv.rows != cam.height_px)
    throw std::invalid_argument("RbpfLocalizer: expected a " + std::to_string(cam.width_px) + "x" +
                                std::to_string(cam.height_px) + " YUV image");
  pixel_yuv_ = pixelValues(yuv, pixels_);
}

template <typename F>
void RbpfLocalizer::parallelFor(size_t n, F&& f) const {
  const int threads = std::min<int>(config_.threads, static_cast<int>(n));
  if (threads <= 1) {
    for (size_t i = 0; i < n; ++i) f(i);
    return;
  }
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (size_t i = t; i < n; i += threads) f(i);
    });
  for (auto& th : pool) th.join();
}

RbpfLocalizer::CoarseImage RbpfLocalizer::coarseImage(
    const cv::Mat& yuv, const Eigen::Isometry3d& base_to_optical) const {
  CoarseImage c;
  c.pixels = pixelGrid(renderer_.camera(), config_.global_pixel_stride, &c.cols);
  c.values = pixelValues(yuv, c.pixels);
  c.offsets = neighbourOffsets(renderer_.camera(), c.pixels, config_.global_pixel_stride,
                               base_to_optical, config_.likelihood);
  return c;
}

void RbpfLocalizer::fillUniformPool(std::vector<math::SE2>* pool, size_t n,
                                    std::uint64_t seed) const {
  parallelFor(n, [&](size_t i) {
    // Pairs of point-mirrored poses (see mirror_fraction): both halves are searched alike.
    math::Rng rng(mix(seed ^ 0x5bd1e995ull, i / 2));
    (*pool)[i] = uniformPose(rng);
    if (i % 2 == 1)
      (*pool)[i] = math::SE2(-(*pool)[i].x_m, -(*pool)[i].y_m,
                             math::wrapAngle((*pool)[i].yaw_rad + math::kPi));
  });
}

void RbpfLocalizer::scorePool(std::vector<math::SE2>* pool, std::vector<double>* ll, size_t first,
                              bool move, const math::SE2& odom_delta, const CoarseImage& image,
                              const color::SwitchingColorFilter& lighting,
                              const Eigen::Isometry3d& base_to_optical) const {
  parallelFor(pool->size() - first, [&](size_t k) {
    const size_t i = first + k;
    if (move) (*pool)[i] = (*pool)[i] * odom_delta;
    (*ll)[i] += logLikelihoodAt(image.pixels, image.cols, image.offsets, image.values, (*pool)[i],
                                lighting, base_to_optical, nullptr, nullptr);
  });
}

void RbpfLocalizer::pushWindow(const math::SE2& odom_delta, CoarseImage image,
                               const color::SwitchingColorFilter& lighting,
                               const Eigen::Isometry3d& base_to_optical, bool reset) {
  if (reset) window_.clear();
  for (WindowFrame& f : window_) f.to_last = f.to_last * odom_delta;
  window_.push_back({std::move(image), math::SE2(), lighting, base_to_optical});
}

double RbpfLocalizer::windowLogLikelihood(const math::SE2& pose_at_last) const {
  double sum = 0.0;
  for (const WindowFrame& f : window_)
    sum += logLikelihoodAt(f.image.pixels, f.image.cols, f.image.offsets, f.image.values,
                           pose_at_last * f.to_last.inverse(), f.lighting, f.base_to_optical,
                           nullptr, nullptr);
  return sum;
}

void RbpfLocalizer::refinePool(std::vector<math::SE2>* pool, std::vector<double>* ll, size_t begin,
                               size_t end, int candidates, std::uint64_t seed) const {
  if (config_.refine_rounds <= 0 || end <= begin || window_.empty()) return;
  std::vector<size_t> top(end - begin);
  for (size_t i = 0; i < top.size(); ++i) top[i] = begin + i;
  const size_t k = std::min<size_t>(top.size(), static_cast<size_t>(std::max(candidates, 0)));
  std::partial_sort(top.begin(), top.begin() + static_cast<std::ptrdiff_t>(k), top.end(),
                    [&](size_t a, size_t b) { return (*ll)[a] > (*ll)[b]; });
  top.resize(k);
  for (int round = 0; round < config_.refine_rounds; ++round) {
    const double scale = std::ldexp(1.0, -round);
    parallelFor(k, [&](size_t c) {
      const size_t i = top[c];
      math::Rng rng(mix(mix(seed, static_cast<std::uint64_t>(round)), i));
      for (int t = 0; t < config_.refine_tries; ++t) {
        const math::SE2& p = (*pool)[i];
        const math::SE2 q(
            p.x_m + rng.gaussian(0.0, scale * config_.refine_sigma_m),
            p.y_m + rng.gaussian(0.0, scale * config_.refine_sigma_m),
            math::wrapAngle(p.yaw_rad + rng.gaussian(0.0, scale * config_.refine_sigma_rad)));
        const double l = windowLogLikelihood(q);
        if (l > (*ll)[i]) {
          (*pool)[i] = q;
          (*ll)[i] = l;
        }
      }
    });
  }
}

std::vector<Particle> RbpfLocalizer::drawFromPool(const std::vector<math::SE2>& pool,
                                                  const std::vector<double>& ll, size_t n,
                                                  int count,
                                                  const color::SwitchingColorFilter& lighting) {
  std::vector<double> w;
  const double target = 0.5 * count;
  auto weigh = [&](double lambda) {
    std::vector<double> logw(n);
    for (size_t i = 0; i < n; ++i) logw[i] = lambda * ll[i];
    math::normalizeLogWeights(logw, &w);
    return math::effectiveSampleSize(w);
  };
  double lo = 0.0, hi = 1.0;
  if (weigh(1.0) >= target) {
    lo = 1.0;
  } else {
    for (int it = 0; it < 30; ++it) {
      const double mid = 0.5 * (lo + hi);
      (weigh(mid) >= target ? lo : hi) = mid;
    }
  }
  weigh(lo);
  const auto idx = math::resampleIndices(w, count, math::ResamplingScheme::kSystematic, rng_);
  std::vector<Particle> out;
  out.reserve(idx.size());
  for (size_t i : idx) out.push_back({pool[i], lighting, 0.0});
  return out;
}

bool RbpfLocalizer::globalSearch(const math::SE2& odom_delta, const cv::Mat& yuv,
                                 const Eigen::Isometry3d& base_to_optical,
                                 std::uint64_t frame_seed) {
  // Score the pool on a coarse pixel grid under the prior lighting, summing over images, and draw
  // the particles from it with the tempering that keeps half of them distinct.
  CoarseImage image = coarseImage(yuv, base_to_optical);
  const color::SwitchingColorFilter lighting(priors_, config_.model, config_.switching);
  const size_t n = static_cast<size_t>(config_.global_pool_size);
  const bool first = pool_.empty();
  if (first) {
    pool_.resize(n);
    pool_ll_.assign(n, 0.0);
    fillUniformPool(&pool_, n, frame_seed);
  }
  scorePool(&pool_, &pool_ll_, 0, !first, odom_delta, image, lighting, base_to_optical);
  ++pool_frames_;
  pushWindow(odom_delta, image, lighting, base_to_optical, first);
  const bool done = pool_frames_ >= config_.global_search_frames;
  if (done) refinePool(&pool_, &pool_ll_, 0, n, config_.refine_candidates, frame_seed);
  particles_ = drawFromPool(pool_, pool_ll_, n, config_.particles, lighting);
  weights_.assign(particles_.size(), 1.0 / particles_.size());
  if (!done) return false;
  global_pending_ = false;
  seconds_since_check_ = 0.0;
  if (config_.global_confirm_frames > config_.global_search_frames) {
    confirm_pending_ = true;  // the pool goes on (confirmSearch)
    return true;
  }
  window_.clear();
  pool_.clear();
  pool_.shrink_to_fit();
  pool_ll_.clear();
  pool_ll_.shrink_to_fit();
  pool_frames_ = 0;
  seconds_since_check_ = 0.0;
  return true;
}

void RbpfLocalizer::relocalizationCheck(const math::SE2& odom_delta, double dt_s,
                                        const cv::Mat& yuv,
                                        const Eigen::Isometry3d& base_to_optical,
                                        std::uint64_t frame_seed, StepResult* result) {
  if (config_.relocalization_interval_s <= 0.0) return;
  const bool starting = check_frames_ == 0;
  if (starting) {
    seconds_since_check_ += std::max(dt_s, 0.0);
    if (seconds_since_check_ < config_.relocalization_interval_s) return;
  }
  // The priors' lighting, as in the global search, not the particles' own (see
  // RbpfConfig::relocalization_interval_s).
  const color::SwitchingColorFilter lighting(priors_, config_.model, config_.switching);
  CoarseImage image = coarseImage(yuv, base_to_optical);
  if (starting) {
    // The particles have this image's motion already; the uniform poses are drawn for it.
    check_uniform_ = static_cast<size_t>(config_.relocalization_pool_size);
    check_pool_.resize(check_uniform_ + particles_.size());
    check_ll_.assign(check_pool_.size(), 0.0);
    fillUniformPool(&check_pool_, check_uniform_, frame_seed ^ 0x2545F4914F6CDD1Dull);
    for (size_t i = 0; i < particles_.size(); ++i)
      check_pool_[check_uniform_ + i] = particles_[i].pose;
  }
  scorePool(&check_pool_, &check_ll_, 0, !starting, odom_delta, image, lighting, base_to_optical);
  pushWindow(odom_delta, image, lighting, base_to_optical, starting);
  if (++check_frames_ < config_.global_search_frames) return;
  finishCheck(lighting, frame_seed,
              {config_.relocalization_margin, config_.relocalization_fraction,
               config_.relocalization_restart, config_.relocalization_refine_candidates},
              result);
}

void RbpfLocalizer::confirmSearch(const math::SE2& odom_delta, const cv::Mat& yuv,
                                  const Eigen::Isometry3d& base_to_optical,
                                  std::uint64_t frame_seed, StepResult* result) {
  CoarseImage image = coarseImage(yuv, base_to_optical);
  const color::SwitchingColorFilter lighting(priors_, config_.model, config_.switching);
  scorePool(&pool_, &pool_ll_, 0, true, odom_delta, image, lighting, base_to_optical);
  pushWindow(odom_delta, image, lighting, base_to_optical, false);
  if (++pool_frames_ < config_.global_confirm_frames) return;
  // The particles' poses are scored over the same images as the pool (each moved back by the
  // odometry) for the score, and global_confirm_fraction of them are drawn from the pool.
  confirm_pending_ = false;
  check_uniform_ = pool_.size();
  check_pool_ = std::move(pool_);
  check_ll_ = std::move(pool_ll_);
  pool_.clear();
  pool_ll_.clear();
  pool_frames_ = 0;
  check_pool_.resize(check_uniform_ + particles_.size());
  check_ll_.resize(check_pool_.size());
  parallelFor(particles_.size(), [&](size_t i) {
    check_pool_[check_uniform_ + i] = particles_[i].pose;
    check_ll_[check_uniform_ + i] = windowLogLikelihood(particles_[i].pose);
  });
  const color::SwitchingColorFilter best_lighting = best().lighting;
  finishCheck(best_lighting, frame_seed,
              {-std::numeric_limits<double>::infinity(), config_.global_confirm_fraction, false,
               config_.refine_candidates},
              result);
  check_pool_.shrink_to_fit();
  check_ll_.shrink_to_fit();
}

void RbpfLocalizer::finishCheck(const color::SwitchingColorFilter& lighting,
                                std::uint64_t frame_seed, const CheckPolicy& policy,
                                StepResult* result) {
  // Both sides are refined alike, so neither wins by having been optimised on these images.
  refinePool(&check_pool_, &check_ll_, 0, check_uniform_, policy.refine_candidates, frame_seed);
  refinePool(&check_pool_, &check_ll_, check_uniform_, check_pool_.size(), policy.refine_candidates,
             frame_seed ^ 0x9E37ull);
  const auto mid = check_ll_.begin() + static_cast<std::ptrdiff_t>(check_uniform_);
  const double best_uniform =
      check_uniform_ > 0 ? *std::max_element(check_ll_.begin(), mid) : -1e300;
  const double best_particle = *std::max_element(mid, check_ll_.end());
  result->relocalization_score = best_uniform - best_particle;
  const bool win = result->relocalization_score > policy.margin && policy.fraction > 0.0;
  if (win && policy.restart) {
    initUniform();  // also ends this check (its pool and window)
    result->relocalized = true;
    return;
  }
  if (win) {
    const int n = static_cast<int>(particles_.size());
    const int fresh = static_cast<int>(std::lround(policy.fraction * n));
    std::vector<Particle> next =
        drawFromPool(check_pool_, check_ll_, check_uniform_, fresh, lighting);
    for (size_t i :
         math::resampleIndices(weights_, n - fresh, math::ResamplingScheme::kSystematic, rng_))
      next.push_back(particles_[i]);
    particles_ = std::move(next);
    weights_.assign(particles_.size(), 1.0 / particles_.size());
    result->relocalized = true;
  }
  check_pool_.clear();
  check_ll_.clear();
  check_frames_ = 0;
  seconds_since_check_ = 0.0;
  window_.clear();
}

RbpfLocalizer::StepResult RbpfLocalizer::step(const math::SE2& odom_delta, double dt_s,
                                              const cv::Mat& yuv,
                                              const Eigen::Isometry3d& base_to_optical) {
  setImage(yuv);
  if (offsets_camera_.matrix() != base_to_optical.matrix()) {
    offsets_ = neighbourOffsets(renderer_.camera(), pixels_, config_.likelihood.pixel_stride,
                                base_to_optical, config_.likelihood);
    offsets_camera_ = base_to_optical;
  }
  const std::uint64_t frame_seed = mix(config_.seed, ++frame_);
  StepResult r;
  bool moved = false;  // the particles already carry this image's odometry (drawn from the pool)
  if (global_pending_) {
    moved = true;
    if (!globalSearch(odom_delta, yuv, base_to_optical, frame_seed)) {
      r.effective_sample_size = math::effectiveSampleSize(weights_);
      return r;  // still searching: the particles show the pool's current belief
    }
  }
  pixels_used_.assign(particles_.size(), 0);
  parallelFor(particles_.size(), [&](size_t i) {
    weighParticle(i, moved ? math::SE2() : odom_delta, dt_s, base_to_optical, frame_seed);
  });
  // Adaptive tempering: when this image alone would leave fewer than min_ess_fraction * N
  // effective particles, its likelihood is flattened by the largest factor lambda <= 1 that keeps
  // them (bisection). A global start or a kidnap then narrows over several frames instead of
  // collapsing onto whichever particle happened to land nearest a peak.
  const std::vector<double> prior_w = weights_;
  auto weigh = [&](double lambda) {
    std::vector<double> logw(particles_.size());
    for (size_t i = 0; i < particles_.size(); ++i)
      logw[i] = std::log(std::max(prior_w[i], 1e-300)) + lambda * particles_[i].log_likelihood;
    math::normalizeLogWeights(logw, &weights_);
    return math::effectiveSampleSize(weights_);
  };
  const double target = config_.min_ess_fraction * particles_.size();
  r.tempering = 1.0;
  if (weigh(1.0) < target && target > 1.0) {
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 30; ++it) {
      const double mid = 0.5 * (lo + hi);
      (weigh(mid) >= target ? lo : hi) = mid;
    }
    r.tempering = lo;
    weigh(lo);
  }
  r.effective_sample_size = math::effectiveSampleSize(weights_);
  // Average likelihood per pixel (untempered), for recovery.
  std::vector<double> ll(particles_.size());
  double pix = 0.0;
  for (size_t i = 0; i < particles_.size(); ++i) {
    ll[i] = particles_[i].log_likelihood / config_.likelihood.exponent;
    pix += pixels_used_[i];
  }
  pix /= particles_.size();
  const double max_ll = *std::max_element(ll.begin(), ll.end());
  double sum = 0.0;
  for (double x : ll) sum += std::exp(x - max_ll);
  const double avg = pix > 0 ? (max_ll + std::log(sum / ll.size())) / pix : 0.0;
  r.mean_pixel_log_likelihood = avg;
  const size_t best_i = std::max_element(weights_.begin(), weights_.end()) - weights_.begin();
  r.pixels_used = pixels_used_[best_i];
  if (pix >= 20) {  // frames that show almost nothing of the field say nothing about kidnapping
    if (!have_average_) {
      w_slow_ = w_fast_ = avg;
      have_average_ = true;
    } else {
      w_slow_ += config_.recovery_alpha_slow * (avg - w_slow_);
      w_fast_ += config_.recovery_alpha_fast * (avg - w_fast_);
    }
  }
  if (r.effective_sample_size < config_.resample_ess_fraction * particles_.size()) {
    const auto idx = math::resampleIndices(weights_, particles_.size(),
                                           math::ResamplingScheme::kSystematic, rng_);
    std::vector<Particle> next;
    next.reserve(particles_.size());
    for (size_t i : idx) next.push_back(particles_[i]);
    particles_ = std::move(next);
    weights_.assign(particles_.size(), 1.0 / particles_.size());
    r.resampled = true;
    // Augmented MCL: replace a share of the particles by uniform ones when the recent likelihood
    // fell.
    const double fraction = std::clamp(config_.recovery_gain_per_nat * (w_slow_ - w_fast_), 0.0,
                                       config_.recovery_max_fraction);
    const int inject = static_cast<int>(std::floor(fraction * particles_.size()));
    for (int k = 0; k < inject; ++k) {
      Particle& p = particles_[rng_.uniformInt(0, static_cast<int>(particles_.size()) - 1)];
      p.pose = uniformPose(rng_);
    }
    r.injected = inject;
    const int mirror = static_cast<int>(std::floor(config_.mirror_fraction * particles_.size()));
    const int n = static_cast<int>(particles_.size());
    for (int k = 0; k < mirror; ++k) {
      const Particle& src = particles_[rng_.uniformInt(0, n - 1)];
      Particle& dst = particles_[rng_.uniformInt(0, n - 1)];
      const math::SE2 m(-src.pose.x_m, -src.pose.y_m,
                        math::wrapAngle(src.pose.yaw_rad + math::kPi));
      dst.lighting = src.lighting;
      dst.pose = m;
      weights_[&dst - particles_.data()] = config_.mirror_relative_weight / particles_.size();
    }
    if (mirror > 0) {
      double total = 0.0;
      for (double w : weights_) total += w;
      for (double& w : weights_) w /= total;
    }
    r.mirrored = mirror;
  }
  if (confirm_pending_ && !moved)
    confirmSearch(odom_delta, yuv, base_to_optical, frame_seed, &r);
  else if (!confirm_pending_)
    relocalizationCheck(moved ? math::SE2() : odom_delta, dt_s, yuv, base_to_optical, frame_seed,
                        &r);
  mirrorTest(moved ? math::SE2() : odom_delta, dt_s, base_to_optical, &r);
  return r;
}

void RbpfLocalizer::resetMirrorTest() {
  mirror_have_pose_ = false;
  mirror_evidence_ = 0.0;
  mirror_lighting_.reset();
}

void RbpfLocalizer::mirrorTest(const math::SE2& odom_delta, double dt_s,
                               const Eigen::Isometry3d& base_to_optical, StepResult* result) {
  if (config_.mirror_test_margin_nats <= 0.0) return;
  auto mirrored = [](const math::SE2& p) {
    return math::SE2(-p.x_m, -p.y_m, p.yaw_rad + math::kPi);
  };
  const math::SE2 pose = estimate().pose;
  if (result->relocalized) mirror_have_pose_ = false;  // the evidence was for another place
  if (!mirror_have_pose_) mirror_evidence_ = 0.0;
  if (mirror_have_pose_) {
    // The evidence belongs to the hypothesis it was summed for: when the estimate moves to the
    // other cluster (the mirror copies can outweigh it for a while) the sum changes sign, and when
    // it jumps anywhere else it starts again. (Starting again on the move to the other cluster as
    // well cost the bright bag: the estimate went back and forth between the clusters, and two
    // seeds in five converged 2.5 and 4.75 s later.)
    const math::SE2 predicted = mirror_pose_ * odom_delta;
    constexpr double kJumpM = 0.5;
    const math::SE2 other = mirrored(predicted);
    if (std::hypot(pose.x_m - predicted.x_m, pose.y_m - predicted.y_m) > kJumpM) {
      if (std::hypot(pose.x_m - other.x_m, pose.y_m - other.y_m) <= kJumpM)
        mirror_evidence_ = -mirror_evidence_;
      else
        mirror_evidence_ = 0.0;
    }
  }
  mirror_lighting_.predict(std::max(dt_s, 0.0));
  color::ColorObservation obs;
  const double ll_pose = imageLogLikelihood(pose, mirror_lighting_, base_to_optical, &obs, nullptr);
  const double ll_mirror =
      imageLogLikelihood(mirrored(pose), mirror_lighting_, base_to_optical, nullptr, nullptr);
  mirror_evidence_ =
      mirror_evidence_ * std::exp(-std::max(dt_s, 0.0) / config_.mirror_test_memory_s) + ll_mirror -
      ll_pose;
  // Only the colours that look alike from both poses teach the reference lighting.
  const auto& classes = config_.model.classes;
  for (size_t k = 0; k < obs.counts.size() && k < classes.size(); ++k)
    if (classes[k] != world::kGreen && classes[k] != world::kWhite) obs.counts[k] = 0;
  mirror_lighting_.update(obs);
  mirror_pose_ = pose;
  mirror_have_pose_ = true;
  if (mirror_evidence_ > config_.mirror_test_margin_nats) {
    // Only the hypothesis the evidence was summed for moves; other clusters (a relocalization's
    // draw) keep their places.
    for (size_t i : mainCluster()) {
      particles_[i].pose = mirrored(particles_[i].pose);
      particles_[i].lighting = mirror_lighting_;
    }
    mirror_pose_ = mirrored(pose);
    mirror_evidence_ = -mirror_evidence_;
    result->mirror_flipped = true;
  }
  result->mirror_evidence = mirror_evidence_;
}

std::vector<size_t> RbpfLocalizer::mainCluster() const {
  // The cell of a coarse (x, y, yaw) grid with the most weight in it and its 26 neighbours (a
  // hypothesis spread over a few cells must outweigh a compact one that holds less weight), then
  // every particle near the weighted mean of that block.
  constexpr double kCell = 0.25, kRadius = 0.5, kYaw = 0.6;
  constexpr int kYawBins = 8;
  using Key = std::tuple<int, int, int>;
  std::map<Key, double> cells;
  auto key = [&](const math::SE2& p) {
    const int b =
        static_cast<int>(std::floor((p.yaw_rad + math::kPi) / (2.0 * math::kPi / kYawBins)));
    return std::make_tuple(static_cast<int>(std::floor(p.x_m / kCell)),
                           static_cast<int>(std::floor(p.y_m / kCell)),
                           ((b % kYawBins) + kYawBins) % kYawBins);
  };
  auto near = [&](const Key& a, const Key& b) {
    const int dyaw = std::abs(std::get<2>(a) - std::get<2>(b));
    return std::abs(std::get<0>(a) - std::get<0>(b)) <= 1 &&
           std::abs(std::get<1>(a) - std::get<1>(b)) <= 1 && std::min(dyaw, kYawBins - dyaw) <= 1;
  };
  for (size_t i = 0; i < particles_.size(); ++i) cells[key(particles_[i].pose)] += weights_[i];
  Key top{};
  double top_weight = -1.0;
  for (const auto& [k, w] : cells) {
    double block = 0.0;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dyaw = -1; dyaw <= 1; ++dyaw) {
          const auto it =
              cells.find(std::make_tuple(std::get<0>(k) + dx, std::get<1>(k) + dy,
                                         (std::get<2>(k) + dyaw + kYawBins) % kYawBins));
          if (it != cells.end()) block += it->second;
        }
    if (block > top_weight) {
      top_weight = block;
      top = k;
    }
  }
  std::vector<size_t> in_block;
  for (size_t i = 0; i < particles_.size(); ++i)
    if (near(key(particles_[i].pose), top)) in_block.push_back(i);
  const math::SE2 c = weightedMean(in_block);
  std::vector<size_t> out;
  for (size_t i = 0; i < particles_.size(); ++i) {
    const math::SE2& p = particles_[i].pose;
    if (std::hypot(p.x_m - c.x_m, p.y_m - c.y_m) < kRadius &&
        std::fabs(math::angleDiff(p.yaw_rad, c.yaw_rad)) < kYaw)
      out.push_back(i);
  }
  return out;
}

math::SE2 RbpfLocalizer::weightedMean(const std::vector<size_t>& idx) const {
  double x = 0, y = 0, c = 0, s = 0, w = 0;
  for (size_t i : idx) {
    x += weights_[i] * particles_[i].pose.x_m;
    y += weights_[i] * particles_[i].pose.y_m;
    c += weights_[i] * std::cos(particles_[i].pose.yaw_rad);
    s += weights_[i] * std::sin(particles_[i].pose.yaw_rad);
    w += weights_[i];
  }
  if (w <= 0.0) return math::SE2();
  return math::SE2(x / w, y / w, std::atan2(s, c));
}

Eigen::Matrix3d RbpfLocalizer::covarianceAbout(const std::vector<size_t>& idx,
                                               const math::SE2& m) const {
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  double w = 0.0;
  for (size_t i : idx) {
    const Eigen::Vector3d d(particles_[i].pose.x_m - m.x_m, particles_[i].pose.y_m - m.y_m,
                            math::angleDiff(particles_[i].pose.yaw_rad, m.yaw_rad));
    cov += weights_[i] * d * d.transpose();
    w += weights_[i];
  }
  return w > 0.0 ? Eigen::Matrix3d(cov / w) : cov;
}

RbpfLocalizer::PoseEstimate RbpfLocalizer::estimate() const {
  std::vector<size_t> all(particles_.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  PoseEstimate e;
  const std::vector<size_t> cluster = mainCluster();
  e.pose = weightedMean(cluster);
  e.covariance = covarianceAbout(cluster, e.pose);
  for (size_t i : cluster) e.cluster_weight += weights_[i];
  e.spread_m = std::sqrt(covarianceAbout(all, weightedMean(all)).topLeftCorner<2, 2>().trace());
  return e;
}

const Particle& RbpfLocalizer::best() const {
  return particles_[std::max_element(weights_.begin(), weights_.end()) - weights_.begin()];
}

}  // namespace adaptive_perception::localization
