// The tracking simulator (papers/001 section 3.4 scenes): same seed, same frames; the ground-truth
// box holds the target's colour; the lambertian rectangle's brightness follows its orbit.
#include "adaptive_perception/sim/tracking_scene.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

using namespace adaptive_perception::sim;

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
