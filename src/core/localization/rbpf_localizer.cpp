#include "adaptive_perception/localization/rbpf_localizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "adaptive_perception/color/field_segmentation.h"
#include "adaptive_perception/color/image_adapted_prior.h"
#include "adaptive_perception/math/gaussian.h"
#include "adaptive_perception/math/parallel_for.h"
#include "adaptive_perception/math/particle_set.h"
#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::localization {

color::ColorModelConfig RbpfConfig::rbpfModelConfig() {
  color::ColorModelConfig c;
  c.min_pixels_per_color = 4;
  c.observation_noise_floor_var = 25.0;
  return c;
}

void RbpfConfig::validate() const {
  fields().validate(*this);
  if (threads < 1 || threads > 256)
    throw std::invalid_argument("threads = " + std::to_string(threads) + " (allowed: 1..256)");
  model.validate();
  switching.validate();
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
  c.search.pixel_stride = scaled(search.pixel_stride);
  c.global.goal_pixel_stride = scaled(global.goal_pixel_stride);
  // The reference: this camera's aspect at the reference width, sampled at the given stride.
  const int ref_h = std::max(1, static_cast<int>(std::lround(camera.height_px / scale)));
  const double ref_count = gridPixelCount(ref_w, ref_h, likelihood.pixel_stride);
  const double count = gridPixelCount(camera.width_px, camera.height_px, c.likelihood.pixel_stride);
  if (ref_count > 0 && count > 0) c.likelihood.exponent = likelihood.exponent * ref_count / count;
  return c;
}

namespace {
const RbpfConfig& validated(const RbpfConfig& config) {
  config.validate();
  return config;
}
}  // namespace

RbpfLocalizer::RbpfLocalizer(const world::FieldMap& map, const world::PinholeCamera& camera,
                             const std::vector<color::LightingPrior>& priors,
                             const RbpfConfig& config)
    : priors_(priors),
      config_(validated(config).forCamera(camera)),
      prior_lighting_(priors, config_.model, config_.switching),
      likelihood_(
          std::make_shared<const ImageLikelihood>(map, camera, config_.model, config_.likelihood)),
      search_(likelihood_, config_.search, config_.threads),
      global_(config_.global),
      relocalization_(config_.relocalization),
      mirror_test_(priors, config_.model, config_.switching, config_.mirror_test),
      rng_(config.seed),
      image_(likelihood_->grid(config_.likelihood.pixel_stride)) {
  initUniform();
}

std::vector<math::SE2> RbpfLocalizer::poses() const {
  std::vector<math::SE2> out(particles_.size());
  for (size_t i = 0; i < particles_.size(); ++i) out[i] = particles_[i].pose;
  return out;
}

void RbpfLocalizer::resetSearches() {
  weights_.assign(particles_.size(), 1.0 / particles_.size());
  global_.stop();
  relocalization_.reset();
  search_.clearWindow();
  mirror_test_.reset();
}

void RbpfLocalizer::initUniform() {
  adapt_pending_ = config_.adapt_priors_to_image;
  balance_ = color::WhiteBalance();
  pitch_offset_rad_ = 0.0;
  particles_.clear();
  const color::SwitchingColorFilter lighting = priorLighting();
  for (int i = 0; i < config_.particles; ++i)
    particles_.push_back({search_.uniformPose(rng_), lighting, 0.0});
  resetSearches();
  global_.start();
}

void RbpfLocalizer::initGaussian(const math::SE2& mean, const Eigen::Matrix3d& cov) {
  adapt_pending_ = config_.adapt_priors_to_image;
  balance_ = color::WhiteBalance();
  pitch_offset_rad_ = 0.0;
  particles_.clear();
  const color::SwitchingColorFilter lighting = priorLighting();
  const math::Gaussian g(Eigen::Vector3d(mean.x_m, mean.y_m, mean.yaw_rad), cov);
  for (int i = 0; i < config_.particles; ++i) {
    const Eigen::VectorXd s = g.sample(rng_);
    particles_.push_back({math::SE2(s[0], s[1], s[2]), lighting, 0.0});
  }
  resetSearches();
}

double RbpfLocalizer::imageLogLikelihood(const math::SE2& pose,
                                         const color::SwitchingColorFilter& lighting,
                                         const Eigen::Isometry3d& base_to_optical,
                                         color::ColorObservation* obs_out, int* used_out) const {
  if (offsets_camera_.matrix() == base_to_optical.matrix())
    return likelihood_->logLikelihood(image_, pose, lighting, base_to_optical, obs_out, used_out);
  SampledImage image = image_;
  likelihood_->setOffsets(base_to_optical, &image);
  return likelihood_->logLikelihood(image, pose, lighting, base_to_optical, obs_out, used_out);
}

void RbpfLocalizer::weighParticle(size_t i, const math::SE2& odom_delta, double dt_s,
                                  const Eigen::Isometry3d& base_to_optical,
                                  std::uint64_t frame_seed) {
  Particle& p = particles_[i];
  math::Rng rng(math::mixSeeds(frame_seed, i));
  p.pose = sampleMotion(p.pose, odom_delta, config_.motion, rng);
  p.lighting.predict(dt_s);
  color::ColorObservation obs;
  p.log_likelihood = likelihood_->logLikelihood(image_, p.pose, p.lighting, base_to_optical, &obs,
                                                &pixels_used_[i]);
  // Section IV-B: the particle's lighting filter takes the colour means under its own labels.
  p.lighting.update(obs);
}

void RbpfLocalizer::setImage(const cv::Mat& yuv) {
  std::shared_ptr<const BackgroundDensity> background;
  if (config_.likelihood.background_from_image) {
    // The field's boundary from the image shrunk (ImageLikelihoodConfig::background_width_px),
    // the colours above it from the whole image.
    const int width = config_.likelihood.background_width_px;
    cv::Mat small = yuv;
    if (yuv.cols > width) {
      const double f = static_cast<double>(width) / yuv.cols;
      cv::resize(yuv, small, cv::Size(), f, f, cv::INTER_AREA);
    }
    const color::FieldSegmentation seg =
        color::segmentFieldYuv(small, color::FieldSegmentationConfig());
    cv::Mat above = seg.labels == world::kBackground;
    if (small.size() != yuv.size()) cv::resize(above, above, yuv.size(), 0, 0, cv::INTER_NEAREST);
    background = std::make_shared<const BackgroundDensity>(yuv, above,
                                                           config_.likelihood.outlier_probability);
  }
  search_.setBackground(background);
  likelihood_->setColours(yuv, &image_, background.get());
}

std::vector<math::SE2> RbpfLocalizer::goalProposals(const cv::Mat& yuv,
                                                    const Eigen::Isometry3d& base_to_optical,
                                                    std::uint64_t frame_seed, int count,
                                                    std::vector<GoalSighting>* seen) const {
  const world::FieldDimensions& d = likelihood_->map().dimensions();
  if (d.goal_post_diameter_m <= 0.0 && !centreCircleFindable(likelihood_->map(), config_.circle))
    return {};
  const color::FieldSegmentation seg =
      color::segmentFieldYuv(yuv, color::FieldSegmentationConfig());
  const std::vector<GoalSighting> sightings = detectGoals(
      yuv, seg, likelihood_->camera(), base_to_optical, likelihood_->map(), config_.goals);
  // The centre circle where no goal is seen (a goal's posts place the robot more sharply).
  const std::optional<CentreCircleSighting> circle =
      sightings.empty()
          ? detectCentreCircle(seg, likelihood_->camera(), base_to_optical, likelihood_->map(),
                               config_.circle, math::mixSeeds(frame_seed, 0xc12c))
          : std::nullopt;
  // Each sighting gets its share of the proposals (a goal's sampled under its own lean: the
  // best's is the one the particles use, and the others are rare).
  std::vector<math::SE2> proposals;
  math::Rng rng(math::mixSeeds(frame_seed, 0x60a1));
  const int sources = static_cast<int>(sightings.size()) + (circle ? 1 : 0);
  const int share = sources > 0 ? count / sources : 0;
  if (share >= 2) {
    for (const GoalSighting& s : sightings)
      for (const math::SE2& p : sampleGoalPoses(s, likelihood_->map(), config_.goals, share, rng))
        proposals.push_back(p);
    if (circle)
      for (const math::SE2& p :
           centreCirclePoses(*circle, likelihood_->map(), config_.circle, share, rng))
        proposals.push_back(p);
  }
  if (seen) *seen = sightings;
  return proposals;
}

cv::Mat RbpfLocalizer::adaptToImage(const cv::Mat& yuv) {
  std::optional<color::FieldSegmentation> seg;  // this image's, made once
  const auto segmentation = [&]() -> const color::FieldSegmentation& {
    if (!seg) seg = color::segmentFieldYuv(yuv, color::FieldSegmentationConfig());
    return *seg;
  };
  // Adapted, but the image it was adapted to gave no balance (no paint in view, or none white
  // enough): every balance_retry_images images another is tried, and once one gives a balance the
  // adaptation is made again on it.
  if (!adapt_pending_ && config_.adapt_priors_to_image && config_.balance_to_paint &&
      balance_.identity && config_.balance_retry_images > 0 &&
      ++unbalanced_images_ % config_.balance_retry_images == 0 &&
      !color::whiteBalanceFromPaint(yuv, segmentation(), config_.white_balance).identity)
    adapt_pending_ = true;
  // An image without carpet (the head up, a dark start-up frame) says nothing: the next one
  // adapts.
  if (adapt_pending_ && cv::countNonZero(segmentation().labels == world::kGreen) >=
                            config_.model.min_pixels_per_color) {
    adapt_pending_ = false;
    unbalanced_images_ = 0;
    cv::Mat image = yuv;
    if (config_.balance_to_paint) {
      balance_ = color::whiteBalanceFromPaint(yuv, segmentation(), config_.white_balance);
      // The segmentation's labels stand (it judges paint and carpet against each other in the
      // same image, which the balance scales alike); the colours are the balanced image's.
      if (!balance_.identity) image = balance_.apply(yuv);
    }
    const std::vector<color::LightingPrior> adapted =
        color::adaptPriorsToImage(priors_, image, segmentation(), config_.model);
    prior_lighting_ = color::SwitchingColorFilter(adapted, config_.model, config_.switching);
    mirror_test_ = MirrorTest(adapted, config_.model, config_.switching, config_.mirror_test);
    for (Particle& p : particles_) p.lighting = prior_lighting_;
    return image;
  }
  return balance_.identity ? yuv : balance_.apply(yuv);
}

void RbpfLocalizer::resample(StepResult* r) {
  const auto idx =
      math::resampleIndices(weights_, particles_.size(), math::ResamplingScheme::kSystematic, rng_);
  std::vector<Particle> next;
  next.reserve(particles_.size());
  for (size_t i : idx) next.push_back(particles_[i]);
  particles_ = std::move(next);
  weights_.assign(particles_.size(), 1.0 / particles_.size());
  r->resampled = true;
  const int mirror = static_cast<int>(std::floor(config_.mirror_fraction * particles_.size()));
  const int n = static_cast<int>(particles_.size());
  for (int k = 0; k < mirror; ++k) {
    const Particle& src = particles_[rng_.uniformInt(0, n - 1)];
    Particle& dst = particles_[rng_.uniformInt(0, n - 1)];
    dst.lighting = src.lighting;
    dst.pose = math::pointMirror(src.pose);
    weights_[&dst - particles_.data()] = config_.mirror_relative_weight / particles_.size();
  }
  if (mirror > 0) {
    double total = 0.0;
    for (double w : weights_) total += w;
    for (double& w : weights_) w /= total;
  }
  r->mirrored = mirror;
}

bool RbpfLocalizer::applyContest(PoseContest contest, const color::SwitchingColorFilter& lighting,
                                 std::uint64_t frame_seed, double margin, double fraction,
                                 bool restart, int refine_candidates, StepResult* result) {
  result->relocalization_score = search_.settle(&contest, refine_candidates, frame_seed);
  search_.clearWindow();
  if (!(result->relocalization_score > margin && fraction > 0.0)) return false;
  if (restart) {
    initUniform();
    result->global_search_restarted = true;
    return true;
  }
  const int n = static_cast<int>(particles_.size());
  const int fresh = static_cast<int>(std::lround(fraction * n));
  std::vector<Particle> next;
  for (size_t i : search_.draw(contest.log_likelihoods, contest.candidates, fresh, rng_))
    next.push_back({contest.poses[i], lighting, 0.0});
  for (size_t i :
       math::resampleIndices(weights_, n - fresh, math::ResamplingScheme::kSystematic, rng_))
    next.push_back(particles_[i]);
  particles_ = std::move(next);
  weights_.assign(particles_.size(), 1.0 / particles_.size());
  return true;
}

RbpfLocalizer::StepResult RbpfLocalizer::step(const math::SE2& odom_delta, double dt_s,
                                              const cv::Mat& image,
                                              const Eigen::Isometry3d& head_base_to_optical) {
  const cv::Mat yuv = adaptToImage(image);
  setImage(yuv);
  const std::uint64_t frame_seed = math::mixSeeds(config_.seed, ++frame_);
  StepResult r;
  // A global search's first image: the goals it shows (and the camera pitch they measure).
  std::vector<math::SE2> proposals;
  if (global_.poolPending()) {
    const int count =
        static_cast<int>(config_.global.goal_pool_share * config_.global.goal_pool_size);
    if (count >= 2 || config_.goal_pitch_correction) {
      std::vector<GoalSighting> sightings;
      proposals = goalProposals(yuv, head_base_to_optical, frame_seed, count, &sightings);
      if (likelihood_->map().dimensions().goal_post_diameter_m > 0.0)
        r.goal_sightings = static_cast<int>(sightings.size());
      if (config_.goal_pitch_correction && !sightings.empty())
        pitch_offset_rad_ = sightings.front().pitch_offset_rad;
    }
  }
  const Eigen::Isometry3d base_to_optical = leanCamera(head_base_to_optical, pitch_offset_rad_);
  r.camera_pitch_offset_rad = pitch_offset_rad_;
  if (offsets_camera_.matrix() != base_to_optical.matrix()) {
    likelihood_->setOffsets(base_to_optical, &image_);
    offsets_camera_ = base_to_optical;
  }
  // While the global search runs, the particles are drawn from its pool, which carries this
  // image's odometry already.
  const bool moved = global_.searching();
  if (moved) {
    GlobalLocalization::SearchStep s =
        global_.searchImage(&search_, odom_delta, yuv, priorLighting(), base_to_optical, frame_seed,
                            config_.particles, rng_, proposals);
    const color::SwitchingColorFilter lighting = priorLighting();
    particles_.clear();
    for (const math::SE2& p : s.poses) particles_.push_back({p, lighting, 0.0});
    weights_.assign(particles_.size(), 1.0 / particles_.size());
    if (!s.committed) {
      r.effective_sample_size = math::effectiveSampleSize(weights_);
      return r;  // still searching: the particles show the pool's current belief
    }
    relocalization_.reset();
  }
  const math::SE2 delta = moved ? math::SE2() : odom_delta;
  pixels_used_.assign(particles_.size(), 0);
  math::parallelFor(particles_.size(), config_.threads,
                    [&](size_t i) { weighParticle(i, delta, dt_s, base_to_optical, frame_seed); });
  std::vector<double> logw(particles_.size());
  for (size_t i = 0; i < particles_.size(); ++i)
    logw[i] = std::log(std::max(weights_[i], 1e-300)) + particles_[i].log_likelihood;
  math::normalizeLogWeights(logw, &weights_);
  r.effective_sample_size = math::effectiveSampleSize(weights_);
  // The average likelihood per pixel (untempered), for the diagnostics.
  double max_ll = -std::numeric_limits<double>::infinity(), pix = 0.0;
  for (size_t i = 0; i < particles_.size(); ++i) {
    max_ll = std::max(max_ll, particles_[i].log_likelihood / config_.likelihood.exponent);
    pix += pixels_used_[i];
  }
  pix /= particles_.size();
  double sum = 0.0;
  for (const Particle& p : particles_)
    sum += std::exp(p.log_likelihood / config_.likelihood.exponent - max_ll);
  r.mean_pixel_log_likelihood = pix > 0 ? (max_ll + std::log(sum / particles_.size())) / pix : 0.0;
  r.pixels_used =
      pixels_used_[std::max_element(weights_.begin(), weights_.end()) - weights_.begin()];
  if (r.effective_sample_size < config_.resample_ess_fraction * particles_.size()) resample(&r);
  // The searches, under the priors' lighting (see relocalization_monitor.h).
  if (global_.confirming() && !moved) {
    if (auto contest = global_.confirmImage(&search_, odom_delta, yuv, priorLighting(),
                                            base_to_optical, poses())) {
      const color::SwitchingColorFilter best_lighting = best().lighting;
      r.second_draw = applyContest(
          std::move(*contest), best_lighting, frame_seed, -std::numeric_limits<double>::infinity(),
          config_.global.confirm_fraction, false, config_.global.refine_candidates, &r);
    }
  } else if (!global_.confirming()) {
    // The check's pool is drawn as the global search's is: goal_pool_share of it around a goal
    // in view (the detection under the head chain's camera, its lean measured anew), the rest
    // uniform.
    const auto propose = [&] {
      const int count =
          static_cast<int>(config_.global.goal_pool_share * config_.relocalization.pool_size);
      return count >= 2 ? goalProposals(yuv, head_base_to_optical, frame_seed, count)
                        : std::vector<math::SE2>();
    };
    if (auto contest =
            relocalization_.observe(&search_, delta, dt_s, yuv, priorLighting(), base_to_optical,
                                    frame_seed, config_.global.search_frames, poses(), propose)) {
      const RelocalizationConfig& rc = config_.relocalization;
      r.relocalization_checked = true;
      r.relocalized = applyContest(std::move(*contest), priorLighting(), frame_seed, rc.margin,
                                   rc.fraction, rc.restart, rc.refine_candidates, &r);
    }
  }
  if (config_.mirror_test.margin_nats > 0.0) {
    const MirrorTest::Result m =
        mirror_test_.observe(estimate().pose, delta, dt_s, r.relocalized || r.second_draw,
                             *likelihood_, image_, yuv, base_to_optical);
    if (m.flip) {
      // Only the hypothesis the evidence was summed for moves; other clusters (a relocalization's
      // draw) keep their places.
      for (size_t i : mainCluster(poses(), weights_)) {
        particles_[i].pose = math::pointMirror(particles_[i].pose);
        particles_[i].lighting = mirror_test_.lighting();
      }
    }
    r.mirror_evidence = m.evidence;
    r.mirror_flipped = m.flip;
  }
  return r;
}

PoseEstimate RbpfLocalizer::estimate() const { return estimatePose(poses(), weights_); }

const Particle& RbpfLocalizer::best() const {
  return particles_[std::max_element(weights_.begin(), weights_.end()) - weights_.begin()];
}

}  // namespace adaptive_perception::localization
