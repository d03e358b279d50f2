#include <gtest/gtest.h>

#include <cmath>

#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/localization/motion_model.h"
#include "adaptive_perception/localization/rbpf_localizer.h"
#include "adaptive_perception/sim/field_simulator.h"

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
  const color::SwitchingColorFilter lighting(s.priors, cfg.model, cfg.switching);
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
    cfg.global_pool_size = 4000;  // the global search from the first image is covered too
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
