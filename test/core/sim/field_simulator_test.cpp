#include "adaptive_perception/sim/field_simulator.h"

#include <gtest/gtest.h>

#include "../refusal.h"
#include "adaptive_perception/math/angles.h"

using namespace adaptive_perception;
using sim::FieldSimConfig;
using sim::FieldSimulator;
using sim::LightingScript;

namespace {
FieldSimConfig shortConfig(LightingScript script, std::uint64_t seed = 1) {
  FieldSimConfig c;
  c.script = script;
  c.seed = seed;
  c.duration_s = 20.0;
  return c;
}
double meanLuma(const cv::Mat& uyvy) {
  double s = 0;
  for (int r = 0; r < uyvy.rows; ++r)
    for (int c = 0; c < uyvy.cols; ++c) s += uyvy.at<cv::Vec2b>(r, c)[1];
  return s / (uyvy.rows * uyvy.cols);
}
}  // namespace

TEST(ColorTemperature, WhitePointIsNeutralAndWarmLightIsRed) {
  const Eigen::Vector3d wp = world::colorTemperatureRgb(5000.0, 5000.0);
  EXPECT_NEAR((wp - Eigen::Vector3d::Ones()).norm(), 0.0, 1e-12);
  const Eigen::Vector3d warm = world::colorTemperatureRgb(3000.0, 5000.0);
  EXPECT_GT(warm[0], 1.0);
  EXPECT_LT(warm[2], 1.0);
  const Eigen::Vector3d cold = world::colorTemperatureRgb(8000.0, 5000.0);
  EXPECT_LT(cold[0], 1.0);
  EXPECT_GT(cold[2], 1.0);
}

TEST(SceneLighting, InverseSquareAndCosineHandComputed) {
  world::SceneLighting l;
  l.ambient_intensity = 0.0;
  world::LightBank b;
  b.position_m = {0, 0, 2};
  b.intensity = 1.0;
  b.color_temperature_k = 5000.0;  // neutral for the default white point
  l.banks = {b};
  // Straight below at the bank's height: full intensity (falloff 1, cosine 1).
  EXPECT_NEAR(l.irradiance({0, 0, 0}, {0, 0, 1})[1], 1.0, 1e-12);
  // At (2, 0, 0): d^2 = 8, falloff 4/8, cosine 2/sqrt(8).
  const double cos_in = 2.0 / std::sqrt(8.0);
  EXPECT_NEAR(l.irradiance({2, 0, 0}, {0, 0, 1})[1],
              0.5 * (world::SceneLighting::kDiffuseFloor +
                     (1 - world::SceneLighting::kDiffuseFloor) * cos_in),
              1e-12);
  l.banks[0].on = false;
  EXPECT_NEAR(l.irradiance({0, 0, 0}, {0, 0, 1}).norm(), 0.0, 1e-12);
}

TEST(FieldSimulator, DeterministicForSeeds) {
  const world::FieldMap map;
  const auto cam = world::PinholeCamera::aiboErs7();
  FieldSimulator a(map, cam, world::HeadChain(), shortConfig(LightingScript::kSwitching, 3));
  FieldSimulator b(map, cam, world::HeadChain(), shortConfig(LightingScript::kSwitching, 3));
  for (double t : {1.0, 2.5, 7.0}) {
    a.advanceTo(t);
    b.advanceTo(t);
    const auto ia = a.renderCamera(), ib = b.renderCamera();
    EXPECT_EQ(cv::norm(ia.uyvy, ib.uyvy, cv::NORM_INF), 0.0);
    EXPECT_EQ(a.state().odom_pose.x_m, b.state().odom_pose.x_m);
  }
  FieldSimulator c(map, cam, world::HeadChain(), shortConfig(LightingScript::kSwitching, 4));
  c.advanceTo(7.0);
  EXPECT_NE(c.state().true_pose.x_m, a.state().true_pose.x_m);
}

// The labels the simulator writes are exactly what the label renderer gives for the true camera
// pose.
TEST(FieldSimulator, LabelsMatchRendererAtTrueCameraPose) {
  const world::FieldMap map;
  const auto cam = world::PinholeCamera::aiboErs7();
  FieldSimulator s(map, cam, world::HeadChain(), shortConfig(LightingScript::kBright));
  const world::LabelRenderer renderer(map, cam);
  std::vector<std::uint8_t> expect(cam.width_px * cam.height_px);
  for (double t : {0.5, 3.0, 9.0}) {
    s.advanceTo(t);
    const auto img = s.renderCamera();
    renderer.renderImage(s.trueCameraPose(), expect.data());
    ASSERT_TRUE(img.labels.isContinuous());
    EXPECT_TRUE(std::equal(expect.begin(), expect.end(), img.labels.ptr<std::uint8_t>(0)));
  }
}

TEST(FieldSimulator, RobotStaysOnTheFieldAndOdometryDrifts) {
  const world::FieldMap map;
  FieldSimConfig cfg = shortConfig(LightingScript::kBright, 5);
  cfg.duration_s = 120.0;
  FieldSimulator s(map, world::PinholeCamera::aiboErs7(), world::HeadChain(), cfg);
  const math::SE2 start = s.state().true_pose;
  double path = 0.0;
  math::SE2 prev = start;
  for (double t = 0.1; t <= 120.0; t += 0.1) {
    s.advanceTo(t);
    const auto& p = s.state().true_pose;
    ASSERT_TRUE(map.isFree(p.x_m, p.y_m, 0.1)) << "at t=" << t << ": " << p.x_m << ", " << p.y_m;
    path += std::hypot(p.x_m - prev.x_m, p.y_m - prev.y_m);
    prev = p;
  }
  EXPECT_GT(path, 0.5 * cfg.walk_speed_mps * 120.0);  // it walks most of the time
  // Odometry integrates from identity; compare its trajectory in start's frame with the truth.
  const math::SE2 truth_rel = math::between(start, s.state().true_pose);
  const double err =
      std::hypot(truth_rel.x_m - s.state().odom_pose.x_m, truth_rel.y_m - s.state().odom_pose.y_m);
  EXPECT_GT(err, 0.05);  // legged odometry is not the truth
}

// The odometry's systematic translation scale shows up as the ratio of measured to true path
// length.
TEST(FieldSimulator, OdometryTranslationScale) {
  const world::FieldMap map;
  FieldSimConfig cfg = shortConfig(LightingScript::kBright, 6);
  cfg.duration_s = 200.0;
  cfg.odom_translation_noise_m_per_sqrt_m = 0.0;
  cfg.odom_rotation_noise_rad_per_sqrt_rad = 0.0;
  FieldSimulator s(map, world::PinholeCamera::aiboErs7(), world::HeadChain(), cfg);
  double truth = 0.0, odom = 0.0;
  auto pt = s.state().true_pose;
  auto po = s.state().odom_pose;
  for (double t = 0.1; t <= 200.0; t += 1.0 / cfg.odom_rate_hz) {
    s.advanceTo(t);
    truth += std::hypot(s.state().true_pose.x_m - pt.x_m, s.state().true_pose.y_m - pt.y_m);
    odom += std::hypot(s.state().odom_pose.x_m - po.x_m, s.state().odom_pose.y_m - po.y_m);
    pt = s.state().true_pose;
    po = s.state().odom_pose;
  }
  EXPECT_NEAR(odom / truth, cfg.odom_translation_scale, 0.005);
}

TEST(FieldSimulator, DarkIsDarkerAndSwitchingSwitches) {
  const world::FieldMap map;
  const auto cam = world::PinholeCamera::aiboErs7();
  FieldSimulator bright(map, cam, world::HeadChain(), shortConfig(LightingScript::kBright, 2));
  FieldSimulator dark(map, cam, world::HeadChain(), shortConfig(LightingScript::kDark, 2));
  double lb = 0, ld = 0;
  for (double t : {1.0, 4.0, 8.0, 12.0}) {
    bright.advanceTo(t);
    dark.advanceTo(t);
    lb += meanLuma(bright.renderCamera().uyvy);
    ld += meanLuma(dark.renderCamera().uyvy);
  }
  EXPECT_LT(ld, 0.8 * lb);

  FieldSimulator sw(map, cam, world::HeadChain(), shortConfig(LightingScript::kSwitching, 2));
  int on_even = 0, on_odd = 0;
  for (const auto& b : sw.lightingAt(1.0).lighting.banks) on_even += b.on;
  for (const auto& b : sw.lightingAt(5.0).lighting.banks) on_odd += b.on;
  EXPECT_EQ(on_even, static_cast<int>(sw.environment().banks.size()));
  EXPECT_GE(on_odd, 1);
  EXPECT_LE(on_odd, 2);
  EXPECT_EQ(sw.lightingAt(5.0).condition, "dark");
}

TEST(FieldSimulator, KidnapTeleportsOnceAndOdometryDoesNotNotice) {
  const world::FieldMap map;
  FieldSimConfig cfg = shortConfig(LightingScript::kKidnap, 8);
  FieldSimulator s(map, world::PinholeCamera::aiboErs7(), world::HeadChain(), cfg);
  s.advanceTo(9.9);
  EXPECT_FALSE(s.state().kidnapped);
  const auto before_true = s.state().true_pose;
  const auto before_odom = s.state().odom_pose;
  s.advanceTo(10.1);
  EXPECT_TRUE(s.state().kidnapped);
  EXPECT_GT(std::hypot(s.state().true_pose.x_m - before_true.x_m,
                       s.state().true_pose.y_m - before_true.y_m),
            1.0);
  EXPECT_LT(std::hypot(s.state().odom_pose.x_m - before_odom.x_m,
                       s.state().odom_pose.y_m - before_odom.y_m),
            0.1);
}

TEST(FieldSimulator, EnvironmentsDiffer) {
  const auto a = sim::FieldEnvironment::draw(1), b = sim::FieldEnvironment::draw(2);
  EXPECT_NE(a.materials.carpet, b.materials.carpet);
  EXPECT_EQ(sim::FieldEnvironment::draw(0).banks.size(), 4u);
  EXPECT_EQ(sim::FieldEnvironment::draw(1).materials.carpet, a.materials.carpet);
}

TEST(FieldSimulator, BadConfigIsRejectedByName) {
  EXPECT_NO_THROW(FieldSimConfig().validate());
  for (const auto& field : FieldSimConfig::fields().all()) {
    FieldSimConfig c;
    field.set(c, field.range.lo - 1.0);
    EXPECT_TRUE(test_support::refusedNaming([&] { c.validate(); }, field.name + " = "));
  }
  FieldSimConfig c;
  c.sensor.sensor.gamma = 0.1;
  EXPECT_TRUE(test_support::refusedNaming([&] { c.validate(); }, "gamma"));
  EXPECT_THROW(sim::parseLightingScript("disco"), std::invalid_argument);
}
