#include "adaptive_perception/localization/appearance_mcl.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/gaussian.h"
#include "adaptive_perception/math/opencv_seed.h"

namespace adaptive_perception::localization {

const config::Fields<AppearanceMclConfig>& AppearanceMclConfig::fields() {
  using C = AppearanceMclConfig;
  using config::closed;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("particles", &C::particles, closed(10, 100000), "number of particles")
          .add("translation_noise_m", &C::translation_noise_m, closed(0, 10),
               "per image, grown as a particle's weight falls (m)")
          .add("rotation_noise_rad", &C::rotation_noise_rad, closed(0, 3), "per image (rad)")
          .add("stable_spread_m", &C::stable_spread_m, closed(0.01, 100),
               "stable: the estimates follow the motion within this RMS (m)")
          .add("stable_min_weight", &C::stable_min_weight, closed(0, 1),
               "stable: the best similarity is at least this")
          .add("full_reinit_after", &C::full_reinit_after, closed(1, 100000),
               "unstable and lost this many images in a row: a global restart")
          .add("unknown_fraction", &C::unknown_fraction, closed(0.01, 1),
               "share of the particles outside the known places that means unknown")
          .add("known_radius_m", &C::known_radius_m, closed(0.01, 100),
               "a particle farther than this from every training pose is outside (m)");
  return f;
}

void AppearanceMclConfig::validate() const {
  fields().validate(*this);
  auto need = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("appearance MCL: ") + what);
  };
  need(translation_noise_m >= 0.0 && rotation_noise_rad >= 0.0, "noise must be >= 0");
  need(weight_noise_gain >= 0.0, "weight_noise_gain must be >= 0");
  need(weight_epsilon > 0.0 && weight_epsilon <= 1.0, "weight_epsilon must be in (0, 1]");
  need(heading_weight_m >= 0.0, "heading_weight_m must be >= 0");
  need(stability_frames >= 1 && stability_frames <= 1000, "stability_frames must be in 1..1000");
  need(stable_spread_m > 0.0, "stable_spread_m must be positive");
  need(stable_min_weight >= 0.0 && stable_min_weight <= 1.0, "stable_min_weight must be in [0, 1]");
  need(reinit_radius_m > 0.0 && reinit_radius_gain_m >= 0.0, "re-initialisation radii");
  need(unknown_fraction > 0.0 && unknown_fraction <= 1.0, "unknown_fraction must be in (0, 1]");
  need(known_radius_m > 0.0, "known_radius_m must be positive");
}

AppearanceMcl::AppearanceMcl(std::vector<PosedFrame> frames, int num_rooms,
                             AppearanceMclConfig config, std::uint64_t seed)
    : frames_(std::move(frames)), num_rooms_(num_rooms), config_(config), rng_(seed) {
  config_.validate();
  if (frames_.empty()) throw std::invalid_argument("appearance MCL: no training frame with a pose");
  if (num_rooms_ < 1) throw std::invalid_argument("appearance MCL: no room");
  const int n = static_cast<int>(frames_.size());
  pose_points_.create(n, 4, CV_32F);
  xy_points_.create(n, 2, CV_32F);
  for (int i = 0; i < n; ++i) {
    const math::SE2& p = frames_[i].pose;
    if (frames_[i].room < 0 || frames_[i].room >= num_rooms_)
      throw std::invalid_argument("appearance MCL: frame with a room out of range");
    pose_points_.at<float>(i, 0) = static_cast<float>(p.x_m);
    pose_points_.at<float>(i, 1) = static_cast<float>(p.y_m);
    pose_points_.at<float>(i, 2) =
        static_cast<float>(config_.heading_weight_m * std::cos(p.yaw_rad));
    pose_points_.at<float>(i, 3) =
        static_cast<float>(config_.heading_weight_m * std::sin(p.yaw_rad));
    xy_points_.at<float>(i, 0) = static_cast<float>(p.x_m);
    xy_points_.at<float>(i, 1) = static_cast<float>(p.y_m);
  }
  {
    // The kd-trees' random split choices seeded: their searches are exact, but which of two
    // equally near frames a query gets depends on the tree, and so would the run.
    const math::ScopedOpenCvSeed seed(0x4d434cULL);
    pose_index_ = std::make_unique<cv::flann::Index>(pose_points_, cv::flann::KDTreeIndexParams(1));
    xy_index_ = std::make_unique<cv::flann::Index>(xy_points_, cv::flann::KDTreeIndexParams(1));
  }
  // The training run's average step (consecutive frames closer than 2 m: one run).
  double sx = 0.0, sy = 0.0, st = 0.0;
  int steps = 0;
  for (int i = 0; i + 1 < n; ++i) {
    const math::SE2 d = math::between(frames_[i].pose, frames_[i + 1].pose);
    if (std::hypot(d.x_m, d.y_m) > 2.0) continue;
    sx += d.x_m;
    sy += d.y_m;
    st += d.yaw_rad;
    ++steps;
  }
  if (steps > 0) average_step_ = math::SE2(sx / steps, sy / steps, st / steps);
  initGlobal();
}

int AppearanceMcl::nearestFrame(const math::SE2& pose) const {
  const float q[4] = {static_cast<float>(pose.x_m), static_cast<float>(pose.y_m),
                      static_cast<float>(config_.heading_weight_m * std::cos(pose.yaw_rad)),
                      static_cast<float>(config_.heading_weight_m * std::sin(pose.yaw_rad))};
  std::vector<int> idx(1);
  std::vector<float> dist(1);
  pose_index_->knnSearch(std::vector<float>(q, q + 4), idx, dist, 1, cv::flann::SearchParams(-1));
  return idx[0];
}

double AppearanceMcl::distanceToKnown(double x_m, double y_m) const {
  std::vector<int> idx(1);
  std::vector<float> dist(1);
  xy_index_->knnSearch(std::vector<float>{static_cast<float>(x_m), static_cast<float>(y_m)}, idx,
                       dist, 1, cv::flann::SearchParams(-1));
  return std::sqrt(static_cast<double>(dist[0]));  // FLANN's L2 gives squared distances
}

void AppearanceMcl::initGlobal() {
  particles_.clear();
  for (int i = 0; i < config_.particles; ++i) {
    const math::SE2& f = frames_[rng_.uniformInt(0, static_cast<int>(frames_.size()) - 1)].pose;
    // One draw per statement: an argument list's order is the compiler's.
    const double dyaw = rng_.gaussian(0.0, 0.3), dy = rng_.gaussian(0.0, 0.3),
                 dx = rng_.gaussian(0.0, 0.3);
    particles_.emplace_back(f.x_m + dx, f.y_m + dy, f.yaw_rad + dyaw);
  }
  weights_.assign(particles_.size(), 1.0 / particles_.size());
  similarity_.assign(particles_.size(), 0.0);
}

void AppearanceMcl::initAround(const math::SE2& c, double radius_m) {
  particles_.clear();
  for (int i = 0; i < config_.particles; ++i) {
    const double r = radius_m * std::sqrt(rng_.uniform()), a = rng_.uniform(-M_PI, M_PI);
    particles_.emplace_back(c.x_m + r * std::cos(a), c.y_m + r * std::sin(a),
                            rng_.uniform(-M_PI, M_PI));
  }
  weights_.assign(particles_.size(), 1.0 / particles_.size());
  similarity_.assign(particles_.size(), 0.0);
}

void AppearanceMcl::initGaussian(const math::SE2& mean, const Eigen::Matrix3d& covariance) {
  if (!covariance.allFinite())
    throw std::invalid_argument("initGaussian: the covariance has a non-finite entry");
  const math::Gaussian g(Eigen::Vector3d::Zero(), covariance);  // throws unless SPD
  particles_.clear();
  for (int i = 0; i < config_.particles; ++i) {
    const Eigen::VectorXd d = g.sample(rng_);
    particles_.emplace_back(mean.x_m + d[0], mean.y_m + d[1], math::wrapAngle(mean.yaw_rad + d[2]));
  }
  weights_.assign(particles_.size(), 1.0 / particles_.size());
  similarity_.assign(particles_.size(), 0.0);
}

void AppearanceMcl::setParticles(std::vector<math::SE2> particles) {
  particles_ = std::move(particles);
  weights_.assign(particles_.size(), 1.0 / std::max<size_t>(1, particles_.size()));
  similarity_.assign(particles_.size(), 0.0);
}

void AppearanceMcl::resample() {
  // Low-variance resampling.
  const size_t n = particles_.size();
  std::vector<math::SE2> out;
  std::vector<double> sim;
  out.reserve(n);
  const double step = 1.0 / n;
  double u = rng_.uniform(0.0, step), c = weights_[0];
  size_t i = 0;
  for (size_t m = 0; m < n; ++m) {
    while (u > c && i + 1 < n) c += weights_[++i];
    out.push_back(particles_[i]);
    sim.push_back(similarity_[i]);
    u += step;
  }
  particles_ = std::move(out);
  similarity_ = std::move(sim);
  weights_.assign(n, 1.0 / n);
}

AppearanceEstimate AppearanceMcl::estimate() const {
  AppearanceEstimate e;
  double sx = 0.0, sy = 0.0, sc = 0.0, ss = 0.0;
  e.room_weights.assign(num_rooms_, 0.0);
  for (size_t i = 0; i < particles_.size(); ++i) {
    const double w = weights_[i];
    sx += w * particles_[i].x_m;
    sy += w * particles_[i].y_m;
    sc += w * std::cos(particles_[i].yaw_rad);
    ss += w * std::sin(particles_[i].yaw_rad);
    e.room_weights[frames_[nearestFrame(particles_[i])].room] += w;
    e.best_weight = std::max(e.best_weight, similarity_[i]);
  }
  e.pose = math::SE2(sx, sy, std::atan2(ss, sc));
  for (size_t i = 0; i < particles_.size(); ++i) {
    const Eigen::Vector3d d(particles_[i].x_m - sx, particles_[i].y_m - sy,
                            math::wrapAngle(particles_[i].yaw_rad - e.pose.yaw_rad));
    e.covariance += weights_[i] * d * d.transpose();
  }
  e.room = static_cast<int>(std::max_element(e.room_weights.begin(), e.room_weights.end()) -
                            e.room_weights.begin());
  return e;
}

AppearanceEstimate AppearanceMcl::step(const std::optional<math::SE2>& odom_delta,
                                       const std::vector<places::FrameMatch>& frame_similarity) {
  // 1. Motion, noisier for particles that matched badly last time.
  const math::SE2 delta = odom_delta ? *odom_delta : average_step_;
  const double w_max = *std::max_element(weights_.begin(), weights_.end());
  for (size_t i = 0; i < particles_.size(); ++i) {
    const double k =
        1.0 + config_.weight_noise_gain * (1.0 - weights_[i] / std::max(w_max, 1e-300));
    const math::SE2 noisy(delta.x_m + rng_.gaussian(0.0, k * config_.translation_noise_m),
                          delta.y_m + rng_.gaussian(0.0, k * config_.translation_noise_m),
                          delta.yaw_rad + rng_.gaussian(0.0, k * config_.rotation_noise_rad));
    particles_[i] = particles_[i] * noisy;
  }
  // 2. Unknown room: many particles left every trained place.
  int outside = 0;
  for (const math::SE2& p : particles_)
    outside += distanceToKnown(p.x_m, p.y_m) > config_.known_radius_m;
  const bool unknown = outside >= config_.unknown_fraction * particles_.size();
  // 3. Weights from the similarity of the nearest training frame.
  std::unordered_map<int, double> sim;
  for (const places::FrameMatch& m : frame_similarity) sim[m.frame] = m.similarity;
  double total = 0.0;
  for (size_t i = 0; i < particles_.size(); ++i) {
    const auto it = sim.find(nearestFrame(particles_[i]));
    similarity_[i] = it == sim.end() ? 0.0 : it->second;
    weights_[i] = config_.weight_epsilon + similarity_[i];
    total += weights_[i];
  }
  for (double& w : weights_) w /= total;
  // 4. Estimate and stability.
  AppearanceEstimate e = estimate();
  e.unknown_room = unknown;
  // The estimates must move as the robot moves: the residual of each estimate against the last
  // one moved by the motion step (a still robot: the estimates themselves).
  const math::SE2 predicted = last_estimate_ ? *last_estimate_ * delta : e.pose;
  last_estimate_ = e.pose;
  recent_.push_back(math::SE2(e.pose.x_m - predicted.x_m, e.pose.y_m - predicted.y_m, 0.0));
  recent_best_.push_back(e.best_weight);
  while (static_cast<int>(recent_.size()) > config_.stability_frames) {
    recent_.pop_front();
    recent_best_.pop_front();
  }
  double vx = 0.0, vy = 0.0, mb = 0.0;
  for (size_t k = 0; k < recent_.size(); ++k) {
    vx += recent_[k].x_m * recent_[k].x_m;
    vy += recent_[k].y_m * recent_[k].y_m;
    mb += recent_best_[k];
  }
  vx /= recent_.size();
  vy /= recent_.size();
  mb /= recent_.size();
  e.stable = static_cast<int>(recent_.size()) == config_.stability_frames &&
             std::sqrt(vx) < config_.stable_spread_m && std::sqrt(vy) < config_.stable_spread_m &&
             mb >= config_.stable_min_weight && e.best_weight >= config_.stable_min_weight;
  // 5. Re-initialisation only when the filter has lost track (the best match is poor).
  if (e.stable) {
    reliable_ = e.pose;
    unstable_run_ = 0;
    resample();
  } else {
    ++unstable_run_;
    const bool lost = e.best_weight < config_.stable_min_weight;
    if (unstable_run_ >= config_.full_reinit_after && lost) {
      initGlobal();
      e.reinitialized = e.full_reinit = true;
      unstable_run_ = 0;
      recent_.clear();
      recent_best_.clear();
      last_estimate_.reset();
    } else if (lost && reliable_) {
      const double level =
          std::clamp(1.0 - mb / std::max(config_.stable_min_weight, 1e-9), 0.0, 1.0);
      initAround(*reliable_, config_.reinit_radius_m + config_.reinit_radius_gain_m * level);
      e.reinitialized = true;
      last_estimate_.reset();
    } else {
      resample();
    }
    e.room = -1;  // not classified while unstable
  }
  if (unknown) e.room = -1;
  return e;
}

}  // namespace adaptive_perception::localization
