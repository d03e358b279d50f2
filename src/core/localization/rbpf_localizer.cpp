#include "adaptive_perception/localization/rbpf_localizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

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
  if (pixel_stride < 1 || pixel_stride > 64)
    throw std::invalid_argument("pixel_stride = " + std::to_string(pixel_stride) +
                                " (allowed: 1..64)");
  if (!(outlier_probability >= 0.0 && outlier_probability < 1.0))
    throw std::invalid_argument("outlier_probability = " + std::to_string(outlier_probability) +
                                " (allowed: 0 <= p < 1)");
  if (!(exponent > 0.0 && exponent <= 1.0))
    throw std::invalid_argument("exponent = " + std::to_string(exponent) +
                                " (allowed: 0 < e <= 1)");
}

color::ColorModelConfig RbpfConfig::rbpfModelConfig() {
  color::ColorModelConfig c;
  c.min_pixels_per_color = 4;
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
  if (!(recovery_max_fraction >= 0.0 && recovery_max_fraction <= 1.0))
    throw std::invalid_argument("recovery_max_fraction = " + std::to_string(recovery_max_fraction) +
                                " (allowed: 0..1)");
  motion.validate();
  likelihood.validate();
  model.validate();
  switching.validate();
}

RbpfLocalizer::RbpfLocalizer(const world::FieldMap& map, const world::PinholeCamera& camera,
                             const std::vector<color::LightingPrior>& priors,
                             const RbpfConfig& config)
    : map_(map), renderer_(map, camera), priors_(priors), config_(config), rng_(config.seed) {
  config_.validate();
  const int s = config_.likelihood.pixel_stride;
  for (int v = s / 2; v < camera.height_px; v += s)
    for (int u = ((v / s) % 2) * (s / 2); u < camera.width_px; u += s)
      pixels_.push_back({static_cast<std::uint16_t>(u), static_cast<std::uint16_t>(v)});
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
}

double RbpfLocalizer::imageLogLikelihood(const math::SE2& pose,
                                         const color::SwitchingColorFilter& lighting,
                                         const Eigen::Isometry3d& base_to_optical,
                                         color::ColorObservation* obs_out, int* used_out) const {
  const Eigen::Isometry3d cam = world::planarToIsometry(pose) * base_to_optical;
  std::vector<std::uint8_t> labels;
  renderer_.renderPixels(cam, pixels_, &labels);
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
  double background = 0.0;
  for (size_t j = 0; j < pixels_.size(); ++j) {
    const int k = slot[labels[j]];
    if (k < 0) {
      // Background (or an unmodelled colour) under this pose: the uniform density. Every pixel must
      // contribute, or poses that see more background would score higher for having fewer terms.
      background += kLogUniformYuv;
      continue;
    }
    for (int m = 0; m < lighting.numModes(); ++m) {
      const double a = log_in + cls[m].logLikelihood(pixel_yuv_[j], k);
      mode_ll[m] += std::max(a, log_out) + std::log1p(std::exp(-std::fabs(a - log_out)));
    }
    ++used;
    ++obs.counts[k];
    obs.means[k] += pixel_yuv_[j];
  }
  double best = -std::numeric_limits<double>::infinity();
  for (int m = 0; m < lighting.numModes(); ++m)
    best = std::max(best, std::log(std::max(mode_p[m], 1e-300)) + mode_ll[m]);
  double sum = 0.0;
  for (int m = 0; m < lighting.numModes(); ++m)
    sum += std::exp(std::log(std::max(mode_p[m], 1e-300)) + mode_ll[m] - best);
  const double ll = background + best + std::log(sum);
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
  pixel_yuv_.resize(pixels_.size());
  for (size_t j = 0; j < pixels_.size(); ++j) {
    const cv::Vec3b c = yuv.at<cv::Vec3b>(pixels_[j].v, pixels_[j].u);
    pixel_yuv_[j] = Eigen::Vector3d(c[0], c[1], c[2]);
  }
}

RbpfLocalizer::StepResult RbpfLocalizer::step(const math::SE2& odom_delta, double dt_s,
                                              const cv::Mat& yuv,
                                              const Eigen::Isometry3d& base_to_optical) {
  setImage(yuv);
  pixels_used_.assign(particles_.size(), 0);
  const std::uint64_t frame_seed = mix(config_.seed, ++frame_);
  const int threads = std::min<int>(config_.threads, static_cast<int>(particles_.size()));
  if (threads <= 1) {
    for (size_t i = 0; i < particles_.size(); ++i)
      weighParticle(i, odom_delta, dt_s, base_to_optical, frame_seed);
  } else {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        for (size_t i = t; i < particles_.size(); i += threads)
          weighParticle(i, odom_delta, dt_s, base_to_optical, frame_seed);
      });
    for (auto& th : pool) th.join();
  }
  StepResult r;
  std::vector<double> logw(particles_.size());
  for (size_t i = 0; i < particles_.size(); ++i)
    logw[i] = std::log(std::max(weights_[i], 1e-300)) + particles_[i].log_likelihood;
  math::normalizeLogWeights(logw, &weights_);
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
  }
  return r;
}

math::SE2 RbpfLocalizer::meanPose() const {
  double x = 0, y = 0, c = 0, s = 0;
  for (size_t i = 0; i < particles_.size(); ++i) {
    x += weights_[i] * particles_[i].pose.x_m;
    y += weights_[i] * particles_[i].pose.y_m;
    c += weights_[i] * std::cos(particles_[i].pose.yaw_rad);
    s += weights_[i] * std::sin(particles_[i].pose.yaw_rad);
  }
  return math::SE2(x, y, std::atan2(s, c));
}

Eigen::Matrix3d RbpfLocalizer::poseCovariance() const {
  const math::SE2 m = meanPose();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < particles_.size(); ++i) {
    const Eigen::Vector3d d(particles_[i].pose.x_m - m.x_m, particles_[i].pose.y_m - m.y_m,
                            math::angleDiff(particles_[i].pose.yaw_rad, m.yaw_rad));
    cov += weights_[i] * d * d.transpose();
  }
  return cov;
}

const Particle& RbpfLocalizer::best() const {
  return particles_[std::max_element(weights_.begin(), weights_.end()) - weights_.begin()];
}

}  // namespace adaptive_perception::localization
