#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/localization/motion_model.h"
#include "adaptive_perception/localization/rbpf_localizer.h"
#include "adaptive_perception/sim/field_simulator.h"
#include "adaptive_perception/world/robot_camera.h"

using namespace adaptive_perception;
using namespace adaptive_perception::localization;

// Sampled motion: mean is the odometry delta, spread matches the configured standard deviations.
TEST(MotionModel, MeanAndSpreadMatchTheConfiguration) {
  MotionModelConfig c;
  const math::SE2 delta(0.3, 0.05, 0.2);
  const Eigen::Vector2d sd = motionNoiseStd(delta, c);
  EXPECT_NEAR(sd[0], 0.2 * std::hypot(0.3, 0.05) + 0.05 * 0.2 + 0.005, 1e-12);
  EXPECT_NEAR(sd[1], 0.2 * 0.2 + 0.2 * std::hypot(0.3, 0.05) + 0.005, 1e-12);
  math::Rng rng(1);
  const int n = 100000;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sq = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    // From the identity the sample is the perturbed delta itself.
    const math::SE2 s = sampleMotion(math::SE2(), delta, c, rng);
    const Eigen::Vector3d v(s.x_m, s.y_m, s.yaw_rad);
    sum += v;
    sq += v.cwiseProduct(v);
  }
  const Eigen::Vector3d mean = sum / n, var = sq / n - mean.cwiseProduct(mean);
  EXPECT_NEAR(mean[0], 0.3, 4 * sd[0] / std::sqrt(n));
  EXPECT_NEAR(mean[1], 0.05, 4 * sd[0] / std::sqrt(n));
  EXPECT_NEAR(mean[2], 0.2, 4 * sd[1] / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(var[0]), sd[0], 0.02 * sd[0]);
  EXPECT_NEAR(std::sqrt(var[2]), sd[1], 0.02 * sd[1]);
}

namespace {
struct Scene {
  world::FieldMap map;
  world::PinholeCamera cam = world::PinholeCamera::aiboErs7();
  world::HeadChain head;
  std::vector<color::LightingPrior> priors = {
      color::LightingPrior::loadYaml(std::string(AP_SOURCE_DIR) + "/config/color_priors/dark.yaml"),
      color::LightingPrior::loadYaml(std::string(AP_SOURCE_DIR) +
                                     "/config/color_priors/bright.yaml")};
};
}  // namespace

// A particle at the true pose outweighs shifted ones on a simulated image (frames that show a
// beacon or goal, where the image says something about the pose).
TEST(Rbpf, TruePoseOutweighsShiftedPoses) {
  Scene s;
  sim::FieldSimConfig sc;
  sc.seed = 1;
  sim::FieldSimulator sim(s.map, s.cam, s.head, sc);
  RbpfConfig cfg;
  RbpfLocalizer rbpf(s.map, s.cam, s.priors, cfg);
  const color::SwitchingColorFilter prior_lighting(s.priors, cfg.model, cfg.switching);
  int frames = 0, wins = 0;
  for (double t = 0.5; t < 20.0; t += 0.5) {
    sim.advanceTo(t);
    const auto img = sim.renderCamera();
    int non_field = 0;
    for (size_t k = 0; k < img.labels.total(); ++k)
      non_field += img.labels.data[k] >= 2 && img.labels.data[k] <= 4;
    if (non_field < 200) continue;  // no beacon or goal in view
    rbpf.setImage(color::unpackUyvy(img.uyvy));
    const Eigen::Isometry3d b2o = s.head.baseToOptical(sim.state().pan_rad, sim.state().tilt_rad);
    const math::SE2 truth = sim.state().true_pose;
    // The lighting as a particle that has stood at the true pose for 10 images would have it: the
    // prior updated with the colour means under the true pose's labels (the prior alone is off
    // for this simulated light, and its errors can favour a pose that sees more of a mis-modelled
    // colour).
    color::SwitchingColorFilter lighting = prior_lighting;
    for (int k = 0; k < 10; ++k) {
      color::ColorObservation obs;
      rbpf.imageLogLikelihood(truth, lighting, b2o, &obs, nullptr);
      lighting.update(obs);
    }
    const double at_truth = rbpf.imageLogLikelihood(truth, lighting, b2o, nullptr, nullptr);
    bool all = true;
    for (const math::SE2& off :
         {math::SE2(0.3, 0, 0), math::SE2(-0.3, 0, 0), math::SE2(0, 0.3, 0), math::SE2(0, 0, 0.3),
          math::SE2(0, 0, -0.3), math::SE2(1.0, 0.5, 0.5)})
      all &= at_truth > rbpf.imageLogLikelihood(truth * off, lighting, b2o, nullptr, nullptr);
    ++frames;
    wins += all;
  }
  ASSERT_GE(frames, 5);
  EXPECT_GE(wins, frames - 1) << wins << " of " << frames << " frames";
}

// The per-particle work gives the same particles whatever the thread count.
TEST(Rbpf, DeterministicAcrossThreadCounts) {
  Scene s;
  sim::FieldSimConfig sc;
  sim::FieldSimulator sim(s.map, s.cam, s.head, sc);
  std::vector<std::vector<double>> results;
  for (int threads : {1, 3}) {
    RbpfConfig cfg;
    cfg.particles = 40;
    cfg.global.pool_size = 4000;  // the global search from the first image is covered too
    cfg.threads = threads;
    cfg.seed = 9;
    RbpfLocalizer rbpf(s.map, s.cam, s.priors, cfg);
    sim::FieldSimulator run(s.map, s.cam, s.head, sc);
    math::SE2 prev_odom = run.state().odom_pose;
    for (double t = 0.25; t <= 2.0; t += 0.25) {
      run.advanceTo(t);
      const auto img = run.renderCamera();
      rbpf.step(math::between(prev_odom, run.state().odom_pose), 0.25, color::unpackUyvy(img.uyvy),
                s.head.baseToOptical(run.state().pan_rad, run.state().tilt_rad));
      prev_odom = run.state().odom_pose;
    }
    std::vector<double> v;
    for (const auto& p : rbpf.particles()) {
      v.push_back(p.pose.x_m);
      v.push_back(p.pose.yaw_rad);
    }
    v.insert(v.end(), rbpf.weights().begin(), rbpf.weights().end());
    results.push_back(v);
  }
  EXPECT_EQ(results[0], results[1]);
}

// The pose estimate follows the main cluster, not the mean of all particles: after initGaussian the
// estimate is near the mean, and its covariance near the sampling covariance.
TEST(Rbpf, EstimateOfAGaussianCloud) {
  Scene s;
  RbpfConfig cfg;
  cfg.particles = 4000;
  RbpfLocalizer rbpf(s.map, s.cam, s.priors, cfg);
  const math::SE2 mean(1.0, -0.5, 0.4);
  rbpf.initGaussian(mean, Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 0.05 * 0.05).asDiagonal());
  const auto e = rbpf.estimate();
  EXPECT_NEAR(e.pose.x_m, 1.0, 0.005);
  EXPECT_NEAR(e.pose.y_m, -0.5, 0.005);
  EXPECT_NEAR(e.pose.yaw_rad, 0.4, 0.005);
  EXPECT_NEAR(std::sqrt(e.covariance(0, 0)), 0.05, 0.005);
  EXPECT_NEAR(std::sqrt(e.covariance(2, 2)), 0.05, 0.005);
  EXPECT_NEAR(e.cluster_weight, 1.0, 1e-9);
  EXPECT_FALSE(rbpf.globalSearchPending());
}

// A uniform start is global: the particles cover the field (spread of metres) and the next image
// triggers the global search.
TEST(Rbpf, UniformStartCoversTheField) {
  Scene s;
  RbpfConfig cfg;
  cfg.particles = 2000;
  RbpfLocalizer rbpf(s.map, s.cam, s.priors, cfg);
  EXPECT_TRUE(rbpf.globalSearchPending());
  const auto e = rbpf.estimate();
  // Uniform over the carpet less the 0.15 m margin, 5.7 x 3.9 m: the x-y spread is
  // sqrt(5.7^2/12 + 3.9^2/12) = 1.99 m (the goal mouths cut out change it by less than 0.01 m).
  EXPECT_NEAR(e.spread_m, 1.99, 0.08);
  EXPECT_LT(e.cluster_weight, 0.2);
}

// The neighbourhood widens the likelihood's peak: a pose 3 cm off loses far less against the true
// pose than under the pixel-exact comparison (which punishes every line twice, where it is
// predicted and where it is seen), while poses 30 cm off lose against the true pose about as
// often as before (not always: a shift along a line that fills the view does not show).
TEST(Rbpf, NeighbourhoodWidensTheTruePeak) {
  Scene s;
  sim::FieldSimConfig sc;
  sc.seed = 2;
  sim::FieldSimulator sim(s.map, s.cam, s.head, sc);
  RbpfConfig exact_cfg, wide_cfg;
  exact_cfg.likelihood.position_tolerance_m = 0.0;
  exact_cfg.likelihood.heading_tolerance_rad = 0.0;
  RbpfLocalizer exact(s.map, s.cam, s.priors, exact_cfg), wide(s.map, s.cam, s.priors, wide_cfg);
  const color::SwitchingColorFilter lighting(s.priors, exact_cfg.model, exact_cfg.switching);
  double drop_exact = 0.0, drop_wide = 0.0;
  int frames = 0, wide_wins = 0, exact_wins = 0;
  for (double t = 0.5; t < 20.0; t += 0.5) {
    sim.advanceTo(t);
    const auto img = sim.renderCamera();
    int white = 0;
    for (size_t k = 0; k < img.labels.total(); ++k) white += img.labels.data[k] == world::kWhite;
    if (white < 500) continue;  // lines in view: the pose shows in the image
    const cv::Mat yuv = color::unpackUyvy(img.uyvy);
    exact.setImage(yuv);
    wide.setImage(yuv);
    const Eigen::Isometry3d b2o = s.head.baseToOptical(sim.state().pan_rad, sim.state().tilt_rad);
    const math::SE2 truth = sim.state().true_pose;
    auto ll = [&](const RbpfLocalizer& r, const math::SE2& off) {
      return r.imageLogLikelihood(truth * off, lighting, b2o, nullptr, nullptr);
    };
    const math::SE2 near(0.03, 0.0, 0.0);
    drop_exact += ll(exact, math::SE2()) - ll(exact, near);
    drop_wide += ll(wide, math::SE2()) - ll(wide, near);
    bool wins = true, wins_exact = true;
    for (const math::SE2& off : {math::SE2(0.3, 0, 0), math::SE2(-0.3, 0, 0), math::SE2(0, 0.3, 0),
                                 math::SE2(0, -0.3, 0)}) {
      wins &= ll(wide, math::SE2()) > ll(wide, off);
      wins_exact &= ll(exact, math::SE2()) > ll(exact, off);
    }
    wide_wins += wins;
    exact_wins += wins_exact;
    ++frames;
  }
  ASSERT_GE(frames, 5);
  EXPECT_GT(drop_exact, 0.0);
  EXPECT_LT(drop_wide, 0.5 * drop_exact) << "exact " << drop_exact << " wide " << drop_wide;
  EXPECT_GE(wide_wins, exact_wins - 0.1 * frames)
      << "the true pose wins in " << wide_wins << " (wide) and " << exact_wins << " (exact) of "
      << frames << " frames";
  EXPECT_GE(wide_wins, frames / 2);
}

// The global search scores the pool over global_search_frames images before the particles commit;
// until then each image redraws them from the pool.
TEST(Rbpf, GlobalSearchSpansTheConfiguredFrames) {
  Scene s;
  sim::FieldSimConfig sc;
  sim::FieldSimulator sim(s.map, s.cam, s.head, sc);
  RbpfConfig cfg;
  cfg.particles = 100;
  cfg.global.pool_size = 2000;
  cfg.global.search_frames = 3;
  RbpfLocalizer rbpf(s.map, s.cam, s.priors, cfg);
  const double uniform_spread = rbpf.estimate().spread_m;
  math::SE2 prev_odom = sim.state().odom_pose;
  for (int k = 1; k <= 3; ++k) {
    sim.advanceTo(0.25 * k);
    const auto img = sim.renderCamera();
    rbpf.step(math::between(prev_odom, sim.state().odom_pose), 0.25, color::unpackUyvy(img.uyvy),
              s.head.baseToOptical(sim.state().pan_rad, sim.state().tilt_rad));
    prev_odom = sim.state().odom_pose;
    EXPECT_EQ(rbpf.globalSearchPending(), k < 3) << "after image " << k;
    EXPECT_EQ(rbpf.particles().size(), 100u);
  }
  EXPECT_LT(rbpf.estimate().spread_m, uniform_spread);
  cfg.global.search_frames = 0;
  EXPECT_THROW(RbpfLocalizer(s.map, s.cam, s.priors, cfg), std::invalid_argument);
}

// The second draw: the pool goes on after the particles commit, and after global_confirm_frames
// images global_confirm_fraction of the particles are drawn from it again (reported as the second
// draw, not as a relocalization); with a fraction of 0 it is only scored.
TEST(Rbpf, SecondDrawOfTheGlobalSearch) {
  Scene s;
  sim::FieldSimConfig sc;
  for (double fraction : {0.5, 0.0}) {
    sim::FieldSimulator sim(s.map, s.cam, s.head, sc);
    RbpfConfig cfg;
    cfg.particles = 100;
    cfg.global.pool_size = 2000;
    cfg.global.search_frames = 3;
    cfg.global.confirm_frames = 5;
    cfg.global.confirm_fraction = fraction;
    RbpfLocalizer rbpf(s.map, s.cam, s.priors, cfg);
    math::SE2 prev_odom = sim.state().odom_pose;
    for (int k = 1; k <= 7; ++k) {
      sim.advanceTo(0.25 * k);
      const auto img = sim.renderCamera();
      const auto r = rbpf.step(math::between(prev_odom, sim.state().odom_pose), 0.25,
                               color::unpackUyvy(img.uyvy),
                               s.head.baseToOptical(sim.state().pan_rad, sim.state().tilt_rad));
      prev_odom = sim.state().odom_pose;
      EXPECT_EQ(std::isnan(r.relocalization_score), k != 5) << "image " << k;
      EXPECT_EQ(r.second_draw, k == 5 && fraction > 0.0) << "image " << k;
      EXPECT_FALSE(r.relocalized) << "image " << k;
      EXPECT_EQ(rbpf.particles().size(), 100u);
    }
  }
  RbpfConfig bad;
  bad.global.confirm_fraction = 1.5;
  EXPECT_THROW(RbpfLocalizer(s.map, s.cam, s.priors, bad), std::invalid_argument);
}

// Mirrored particles keep the other half's hypothesis alive without moving weight to it: after a
// resampling each weighs mirror_relative_weight w of the others: 1 / (N - m + m w) against
// w / (N - m + m w) for the m mirrored.
TEST(Rbpf, MirroredParticlesCarryTheirRelativeWeight) {
  Scene s;
  sim::FieldSimConfig sc;
  sim::FieldSimulator sim(s.map, s.cam, s.head, sc);
  RbpfConfig cfg;
  cfg.particles = 400;
  cfg.resample_ess_fraction = 1.0;  // resample at every image
  cfg.mirror_fraction = 0.1;
  cfg.mirror_relative_weight = 0.05;
  RbpfLocalizer rbpf(s.map, s.cam, s.priors, cfg);
  const math::SE2 truth = sim.state().true_pose;
  rbpf.initGaussian(truth, Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal());
  sim.advanceTo(0.25);
  const auto img = sim.renderCamera();
  const auto r = rbpf.step(math::SE2(), 0.25, color::unpackUyvy(img.uyvy),
                           s.head.baseToOptical(sim.state().pan_rad, sim.state().tilt_rad));
  ASSERT_TRUE(r.resampled);
  EXPECT_EQ(r.mirrored, 40);
  // m particles were overwritten by a mirror (a copy of a copy goes back to the true half).
  const double max_w = *std::max_element(rbpf.weights().begin(), rbpf.weights().end());
  int m = 0;
  for (double x : rbpf.weights()) m += x < 0.5 * max_w;
  ASSERT_GT(m, 30);  // 40 draws of a destination, a few of them the same particle
  ASSERT_LE(m, 40);
  const double n = cfg.particles, w = cfg.mirror_relative_weight;
  for (size_t i = 0; i < rbpf.particles().size(); ++i) {
    const math::SE2& p = rbpf.particles()[i].pose;
    const bool low = rbpf.weights()[i] < 0.5 * max_w;
    EXPECT_NEAR(rbpf.weights()[i], (low ? w : 1.0) / (n - m + m * w), 1e-12);
    if (std::hypot(p.x_m + truth.x_m, p.y_m + truth.y_m) < 0.2) {
      EXPECT_TRUE(low);
    }
  }
  double total = 0.0;
  for (double x : rbpf.weights()) total += x;
  EXPECT_NEAR(total, 1.0, 1e-9);
}

namespace {
// Runs the localizer from a Gaussian start over `seconds` of the simulator (4 images a second);
// returns the final position error, or the error to the truth's point mirror (-x, -y, yaw + pi) if
// that is smaller and `or_mirror` is set, and counts the relocalizations.
double runFrom(const Scene& s, const sim::FieldSimConfig& sc, const RbpfConfig& cfg,
               const math::SE2& start, double seconds, int* relocalizations, double* max_score,
               bool or_mirror = false, int* mirror_flips = nullptr) {
  sim::FieldSimulator sim(s.map, s.cam, s.head, sc);
  RbpfLocalizer rbpf(s.map, s.cam, s.priors, cfg);
  rbpf.initGaussian(start, Eigen::Vector3d(0.01, 0.01, 0.005).asDiagonal());
  math::SE2 prev_odom = sim.state().odom_pose;
  *relocalizations = 0;
  *max_score = -1e300;
  if (mirror_flips) *mirror_flips = 0;
  for (double t = 0.25; t <= seconds + 1e-9; t += 0.25) {
    sim.advanceTo(t);
    const auto img = sim.renderCamera();
    const auto r = rbpf.step(math::between(prev_odom, sim.state().odom_pose), 0.25,
                             color::unpackUyvy(img.uyvy),
                             s.head.baseToOptical(sim.state().pan_rad, sim.state().tilt_rad));
    prev_odom = sim.state().odom_pose;
    *relocalizations += r.relocalized;
    if (mirror_flips) *mirror_flips += r.mirror_flipped;
    if (!std::isnan(r.relocalization_score))
      *max_score = std::max(*max_score, r.relocalization_score);
  }
  const math::SE2 e = rbpf.estimate().pose, truth = sim.state().true_pose;
  const double error = std::hypot(e.x_m - truth.x_m, e.y_m - truth.y_m);
  const double mirror = std::hypot(e.x_m + truth.x_m, e.y_m + truth.y_m);
  return or_mirror ? std::min(error, mirror) : error;
}
}  // namespace

// The relocalization check undoes a wrong start (as after a kidnap): the particles start 1.4 m and
// 1 rad from the truth; without the check they stay lost, with it (by default: a restart of the
// global search when it wins; or half the particles drawn from its poses) they end at the truth or
// at its point mirror (the field's lines are point-symmetric; which half it is, only the goal and
// beacon colours tell, and this sequence shows them too briefly: see the localization README
// section). Three tests, one run each, so that the sanitizer run spreads them over the cores.
namespace {
// The simulated robot's first true pose for the route of `sc`.
math::SE2 trueStart(const Scene& s, const sim::FieldSimConfig& sc) {
  return sim::FieldSimulator(s.map, s.cam, s.head, sc).state().true_pose;
}

math::SE2 wrongStart(const Scene& s, const sim::FieldSimConfig& sc) {
  const math::SE2 truth = trueStart(s, sc);
  return math::SE2(truth.x_m + (truth.x_m > 0 ? -1.0 : 1.0),
                   truth.y_m + (truth.y_m > 0 ? -1.0 : 1.0), truth.yaw_rad + 1.0);
}

void expectRecoveryFromAWrongStart(bool restart) {
  Scene s;
  sim::FieldSimConfig sc;
  sc.seed = 1;
  RbpfConfig cfg;
  cfg.threads = 2;
  cfg.relocalization.restart = restart;
  int relocalizations = 0;
  double max_score = 0.0;
  const double found =
      runFrom(s, sc, cfg, wrongStart(s, sc), 8.0, &relocalizations, &max_score, true);
  EXPECT_LT(found, 0.3);  // evaluate_localization's convergence bound
  EXPECT_GE(relocalizations, 1);
  EXPECT_GT(max_score, cfg.relocalization.margin);
}
}  // namespace

// The same on the SPL field with its landmarks and a NAO's top camera, whose goals are posts: a
// wrong start is found lost and restarted, a right one is left alone. (The check's pool is drawn
// around a goal in view; this route's checks see none, so their pools are uniform here. The goal's
// pool is tested by RelocalizationMonitor's unit test and on real images by
// evaluate_field_localization: docs/field_localization.md.)
namespace {
Scene naoScene() {
  Scene s;
  const std::string config = std::string(AP_SOURCE_DIR) + "/config/";
  s.map = world::FieldMap::loadYaml(config + "field_spl_landmarks.yaml");
  const world::RobotCamera nao = world::RobotCamera::loadYaml(config + "cameras/nao_v6_top.yaml");
  s.cam = nao.camera;
  s.head = nao.head;
  return s;
}

// The simulated NAO (seed 1; route, head and light as for the AIBO) from the wrong start or the
// true one, 8 s with the defaults; the final error (or to the truth's mirror, from the wrong start).
double runOnNaoField(bool wrong, int* relocalizations, double* max_score) {
  const Scene s = naoScene();
  sim::FieldSimConfig sc;
  sc.seed = 1;
  RbpfConfig cfg;
  cfg.threads = 2;
  return runFrom(s, sc, cfg, wrong ? wrongStart(s, sc) : trueStart(s, sc), 8.0, relocalizations,
                 max_score, wrong);
}
}  // namespace

TEST(Rbpf, OnTheNaoFieldTheCheckRecoversAWrongStart) {
  int relocalizations = 0;
  double max_score = 0.0;
  EXPECT_LT(runOnNaoField(true, &relocalizations, &max_score), 0.3);
  EXPECT_GE(relocalizations, 1);
}

TEST(Rbpf, OnTheNaoFieldTheCheckLeavesARightStartAlone) {
  int relocalizations = 0;
  double max_score = 0.0;
  EXPECT_LT(runOnNaoField(false, &relocalizations, &max_score), 0.3);
  EXPECT_EQ(relocalizations, 0) << "the largest margin a check's pose had: " << max_score;
}

TEST(Rbpf, AWrongStartStaysLostWithoutTheRelocalizationCheck) {
  Scene s;
  sim::FieldSimConfig sc;
  sc.seed = 1;
  RbpfConfig cfg;
  cfg.threads = 2;
  cfg.relocalization.interval_s = 0.0;
  int relocalizations = 0;
  double max_score = 0.0;
  const double lost = runFrom(s, sc, cfg, wrongStart(s, sc), 8.0, &relocalizations, &max_score);
  EXPECT_GT(lost, 0.5) << "the wrong start must stay lost without the check";
  EXPECT_EQ(relocalizations, 0);
}

TEST(Rbpf, RelocalizationCheckRecoversFromAWrongStartByRestartingTheSearch) {
  expectRecoveryFromAWrongStart(true);
}

TEST(Rbpf, RelocalizationCheckRecoversFromAWrongStartByDrawingHalfTheParticles) {
  expectRecoveryFromAWrongStart(false);
}

// On a correct track the check finds nothing better than the particles: no relocalization, and the
// best uniform pose stays below the margin.
TEST(Rbpf, RelocalizationCheckLeavesACorrectTrackAlone) {
  Scene s;
  sim::FieldSimConfig sc;
  sc.seed = 1;
  const math::SE2 truth = trueStart(s, sc);
  RbpfConfig cfg;
  cfg.particles = 200;
  cfg.threads = 2;
  cfg.relocalization.pool_size = 3000;
  cfg.relocalization.interval_s = 1.0;
  int relocalizations = 0;
  double max_score = 0.0;
  const double error = runFrom(s, sc, cfg, truth, 8.0, &relocalizations, &max_score);
  EXPECT_LT(error, 0.15);
  EXPECT_EQ(relocalizations, 0);
  EXPECT_LT(max_score, cfg.relocalization.margin);
  cfg.relocalization.fraction = 0.0;
  EXPECT_THROW(RbpfLocalizer(s.map, s.cam, s.priors, cfg), std::invalid_argument);
}

// The mirror test moves a track that started on the point mirror of the truth over to the truth
// once the goals and beacons have been in view; without it the particles stay on the mirror (the
// lines fit there as well, and each particle's lighting learns the swapped goal colours).
TEST(Rbpf, MirrorTestMovesAMirroredTrackToTheTruth) {
  Scene s;
  sim::FieldSimConfig sc;
  sc.seed = 2;
  const math::SE2 truth = trueStart(s, sc);
  RbpfConfig cfg;
  cfg.particles = 300;
  cfg.threads = 2;
  cfg.mirror_fraction = 0.0;  // no mirror copies: only the test can cross over
  // Nor the relocalization check, which also finds the truth from the mirror (the uniform poses
  // are scored under the priors' lighting, not the particles' learnt swapped goal colours).
  cfg.relocalization.interval_s = 0.0;
  int relocalizations = 0, flips = 0;
  double max_score = 0.0;
  cfg.mirror_test.margin_nats = 0.0;
  const double stays = runFrom(s, sc, cfg, math::pointMirror(truth), 10.0, &relocalizations,
                               &max_score, false, &flips);
  EXPECT_GT(stays, 0.5) << "without the test the track must stay on the mirror";
  EXPECT_EQ(flips, 0);
  cfg.mirror_test.margin_nats = 3.0;
  const double moved = runFrom(s, sc, cfg, math::pointMirror(truth), 10.0, &relocalizations,
                               &max_score, false, &flips);
  EXPECT_LT(moved, 0.15);
  EXPECT_GE(flips, 1);
}

// A camera faster than view_interval_s adds each image's ratio as a share of one view: a second of
// the same image gives the evidence of four views at 30 Hz as at 4 Hz, where counting every frame
// as a view summed the same ratio 7.5 times as often.
TEST(Rbpf, MirrorTestCountsViewsNotFrames) {
  Scene s;
  sim::FieldSimConfig sc;
  sc.seed = 1;
  sim::FieldSimulator sim(s.map, s.cam, s.head, sc);
  RbpfConfig cfg;
  const ImageLikelihood likelihood(s.map, s.cam, cfg.model, cfg.likelihood);
  SampledImage image = likelihood.grid(cfg.likelihood.pixel_stride);
  cv::Mat yuv;
  // A view with a beacon or goal in it, where the pose and its mirror score apart.
  for (double t = 0.5;; t += 0.5) {
    ASSERT_LT(t, 20.0) << "no beacon or goal in view";
    sim.advanceTo(t);
    const auto img = sim.renderCamera();
    int non_field = 0;
    for (size_t k = 0; k < img.labels.total(); ++k)
      non_field += img.labels.data[k] >= 2 && img.labels.data[k] <= 4;
    if (non_field < 200) continue;
    yuv = color::unpackUyvy(img.uyvy);
    likelihood.setColours(yuv, &image, nullptr);
    break;
  }
  const Eigen::Isometry3d b2o = s.head.baseToOptical(sim.state().pan_rad, sim.state().tilt_rad);
  likelihood.setOffsets(b2o, &image);
  const auto evidence = [&](double dt_s, int frames, double view_interval_s) {
    MirrorTestConfig mc;
    mc.margin_nats = 1e6;  // never flips: the sum alone
    mc.view_interval_s = view_interval_s;
    MirrorTest test(s.priors, cfg.model, cfg.switching, mc);
    double e = 0.0;
    for (int k = 0; k < frames; ++k)
      e = test.observe(sim.state().true_pose, math::SE2(), dt_s, false, likelihood, image, yuv,
                       b2o)
              .evidence;
    return e;
  };
  const double at_4hz = evidence(0.25, 4, 0.25), at_30hz = evidence(1.0 / 30.0, 30, 0.25);
  const double per_frame = evidence(1.0 / 30.0, 30, 1e-3);  // every frame a view (the old rule)
  ASSERT_LT(at_4hz, -0.1) << "the truth must beat its mirror on this view";
  // The same ratio r each image: 4 views fading by e^(-0.25/4) against 30 frames of 1/7.5 view
  // fading by e^(-1/120): sums r (1 - e^-0.25) / (1 - e^-0.0625) and r (1 - e^-0.25) / 7.5 /
  // (1 - e^-(1/120)), within 3% of each other; the reference lighting's learning moves r a little.
  EXPECT_NEAR(at_30hz / at_4hz, 1.0, 0.1);
  EXPECT_GT(per_frame / at_4hz, 6.0);
}

// On a track that starts at the truth the test never moves the particles.
TEST(Rbpf, MirrorTestLeavesATrueTrackAlone) {
  Scene s;
  for (std::uint64_t seed : {1, 2}) {
    sim::FieldSimConfig sc;
    sc.seed = seed;
    const math::SE2 truth = trueStart(s, sc);
    RbpfConfig cfg;
    cfg.particles = 300;
    cfg.threads = 2;
    int relocalizations = 0, flips = 0;
    double max_score = 0.0;
    const double error =
        runFrom(s, sc, cfg, truth, 10.0, &relocalizations, &max_score, false, &flips);
    EXPECT_LT(error, 0.15) << "seed " << seed;
    EXPECT_EQ(flips, 0) << "seed " << seed;
  }
  RbpfConfig bad;
  bad.mirror_test.memory_s = 0.0;
  EXPECT_THROW(RbpfLocalizer(s.map, s.cam, s.priors, bad), std::invalid_argument);
}

// The likelihood does not depend on the camera's resolution: the same scene seen by the ERS-7's
// 208 x 160 camera and by 320 x 240 and 640 x 480 cameras of the same field of view is tracked
// from the true start with the default configuration, within the rostests' bound (0.2 m).
// (Absolute strides with an exponent tuned for some 2,000 pixels diverged at 640 x 480.)
// One case per resolution, so that the sanitizer run spreads them over the cores.
class RbpfAtResolution : public ::testing::TestWithParam<std::pair<int, int>> {};

TEST_P(RbpfAtResolution, TracksTheSameScene) {
  const double kHfov = 56.9 * M_PI / 180.0, kVfov = 45.2 * M_PI / 180.0;
  const auto [w, h] = GetParam();
  Scene s;
  s.cam = world::PinholeCamera::fromFieldOfView(w, h, kHfov, kVfov);
  sim::FieldSimConfig sc;
  sc.seed = 2;
  const math::SE2 truth = trueStart(s, sc);
  RbpfConfig cfg;
  cfg.threads = 2;
  int relocalizations = 0;
  double max_score = 0.0;
  const double error = runFrom(s, sc, cfg, truth, 10.0, &relocalizations, &max_score);
  std::printf("rbpf at %d x %d: final error %.3f m, %d relocalizations\n", w, h, error,
              relocalizations);
  EXPECT_LT(error, 0.2) << w << " x " << h;
}

INSTANTIATE_TEST_SUITE_P(Rbpf, RbpfAtResolution,
                         ::testing::Values(std::pair<int, int>{208, 160},
                                           std::pair<int, int>{320, 240},
                                           std::pair<int, int>{640, 480}),
                         [](const ::testing::TestParamInfo<std::pair<int, int>>& info) {
                           return std::to_string(info.param.first) + "x" +
                                  std::to_string(info.param.second);
                         });
