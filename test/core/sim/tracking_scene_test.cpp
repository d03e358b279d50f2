// The tracking simulator (papers/001 section 3.4 scenes): same seed, same frames; the ground-truth
// box holds the target's colour; the lambertian rectangle's brightness follows its orbit.
#include "adaptive_perception/sim/tracking_scene.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "../refusal.h"

using namespace adaptive_perception::sim;
using adaptive_perception::test_support::refusedNaming;

TEST(TrackingScene, SameSeedSameFramesAndTruthOnTheTarget) {
  for (const std::string& name : trackingScenarioNames()) {
    TrackingSceneConfig c;
    c.scenario = parseTrackingScenario(name);
    c.frames = 40;
    TrackingScene a(c, 5), b(c, 5), other(c, 6);
    bool differs = false;
    while (!a.done()) {
      const SceneFrame fa = a.next(), fb = b.next(), fo = other.next();
      ASSERT_EQ(cv::norm(fa.bgr, fb.bgr, cv::NORM_INF), 0.0) << name;
      ASSERT_EQ(fa.truth, fb.truth);
      differs |= cv::norm(fa.bgr, fo.bgr, cv::NORM_INF) > 0.0;
      // The truth box is inside the image and not empty.
      EXPECT_GT(fa.truth.area(), 100.0) << name;
      EXPECT_GE(fa.truth.x, -1.0);
      EXPECT_LE(fa.truth.x + fa.truth.width, c.width + 1.0);
    }
    EXPECT_TRUE(differs) << name << ": another seed gives the same frames";
    EXPECT_THROW(a.next(), std::out_of_range);
  }
  EXPECT_THROW(parseTrackingScenario("faces"), std::invalid_argument);
}

TEST(TrackingSceneConfig, ValidateNamesEachFieldPastItsRange) {
  EXPECT_NO_THROW(TrackingSceneConfig().validate());
  for (const auto& field : TrackingSceneConfig::fields().all()) {
    TrackingSceneConfig c;
    field.set(c, field.range.hi + 1.0);
    EXPECT_TRUE(refusedNaming([&] { c.validate(); }, field.name + " = "));
  }
  TrackingSceneConfig c;
  c.width = 63;
  EXPECT_EQ(adaptive_perception::test_support::refusal([&] { c.validate(); }),
            "width = 63 (allowed: [64, 4096])");
}

TEST(TrackingScene, TheTargetIsReddishAtTheStartAndTheRectangleDimsAwayFromTheLight) {
  TrackingSceneConfig c;
  c.noise_sd = 0.0;
  c.scenario = TrackingScenario::kCircles;
  TrackingScene circles(c, 1);
  const SceneFrame f = circles.next();
  const cv::Point centre(static_cast<int>(f.truth.x + f.truth.width / 2),
                         static_cast<int>(f.truth.y + f.truth.height / 2));
  const cv::Vec3b px = f.bgr.at<cv::Vec3b>(centre);
  EXPECT_GT(px[2], px[1] + 60);  // red well above green at the centre of the box
  c.scenario = TrackingScenario::kLambertianRectangle;
  c.frames = 240;
  TrackingScene rect(c, 1);
  auto meanRed = [](const SceneFrame& s) {
    const cv::Rect2d& b = s.truth;
    const cv::Rect inner(static_cast<int>(b.x + b.width * 0.4),
                         static_cast<int>(b.y + b.height * 0.4), static_cast<int>(b.width * 0.2),
                         static_cast<int>(b.height * 0.2));
    return cv::mean(s.bgr(inner))[2];
  };
  const double facing = meanRed(rect.next());  // orbit angle 0: facing the light
  for (int k = 1; k < 120; ++k) rect.next();
  const double away = meanRed(rect.next());  // half an orbit later: turned away
  EXPECT_GT(facing, 2.5 * away);
}

TEST(TrackingScene, HandheldRampsTheLightAndSwingsTheCardsSize) {
  TrackingSceneConfig c;
  c.scenario = TrackingScenario::kHandheld;
  c.frames = 200;
  TrackingScene scene(c, 1);
  std::vector<SceneFrame> f;
  while (!scene.done()) f.push_back(scene.next());
  // Light 0.4 of full at the start, 1.15 at the middle (clipped to 255 in places).
  const double dim = cv::mean(f[0].bgr)[2], bright = cv::mean(f[100].bgr)[2];
  EXPECT_GT(bright, 2.0 * dim);
  // Size 1 + sin(2 pi k / 200) / 3: 4/3 at frame 50, 2/3 at frame 150.
  EXPECT_NEAR(f[50].truth.width / f[150].truth.width, 2.0, 0.1);
  // The camera moves: the background at a fixed pixel changes between frames.
  EXPECT_GT(cv::norm(f[10].bgr(cv::Rect(0, 0, 20, 20)), f[11].bgr(cv::Rect(0, 0, 20, 20))), 0.0);
}

TEST(TrackingScene, TeamPutsANarrowPlayerAmongTeammatesInTheSameKit) {
  TrackingSceneConfig c;
  c.scenario = TrackingScenario::kTeam;
  c.noise_sd = 0.0;
  TrackingScene scene(c, 1);
  const SceneFrame f = scene.next();
  // 14.4 x 48 px at 320 x 240: a narrow, upright target.
  EXPECT_NEAR(f.truth.width, 14.4, 1e-9);
  EXPECT_NEAR(f.truth.height, 48.0, 1e-9);
  // The kit's shirt colour (bgr 30, 190, 235) is inside the target's box and, as much again at
  // least, outside it: the colour alone does not single the target out.
  cv::Mat shirt;
  cv::inRange(f.bgr, cv::Scalar(25, 185, 230), cv::Scalar(35, 195, 240), shirt);
  const cv::Rect box = cv::Rect(f.truth) & cv::Rect(0, 0, c.width, c.height);
  const int inside = cv::countNonZero(shirt(box)), all = cv::countNonZero(shirt);
  EXPECT_GT(inside, 100);
  EXPECT_GE(all - inside, 2 * inside);
}

TEST(TrackingScene, SprintPansAfterARunnerAmongRunners) {
  TrackingSceneConfig c;
  c.scenario = TrackingScenario::kSprint;
  c.frames = 60;
  TrackingScene scene(c, 1);
  std::vector<SceneFrame> f;
  while (!scene.done()) f.push_back(scene.next());
  // The camera follows the runner: 60 frames at 3.5 px a frame move it 210 px in the scene, but
  // it stays within the middle half of the image, while the background streams past.
  for (const SceneFrame& frame : f) {
    const double cx = frame.truth.x + frame.truth.width / 2;
    EXPECT_GT(cx, 0.25 * c.width);
    EXPECT_LT(cx, 0.75 * c.width);
  }
  EXPECT_GT(cv::norm(f[30].bgr(cv::Rect(0, 0, 40, 40)), f[31].bgr(cv::Rect(0, 0, 40, 40))), 0.0);
}
