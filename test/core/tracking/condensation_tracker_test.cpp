// The CONDENSATION tracker as a whole (condensation_tracker.h) on hand-drawn scenes whose truth is
// known exactly: a disc that moves and changes colour among grey-blue clutter, one that vanishes
// and comes back elsewhere, and a target whose colour also fills its surroundings.
#include "adaptive_perception/tracking/condensation_tracker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

#include "../refusal.h"

using namespace adaptive_perception::tracking;
using adaptive_perception::test_support::refusedNaming;

namespace {

cv::Mat clutter(int seed) {
  std::mt19937 gen(seed);
  std::uniform_int_distribution<int> u(0, 255);
  cv::Mat bg(240, 320, CV_8UC3, cv::Scalar(40, 40, 40));
  for (int i = 0; i < 50; ++i)
    cv::rectangle(bg, cv::Rect{u(gen) % 300, u(gen) % 220, 8 + u(gen) % 30, 8 + u(gen) % 30},
                  cv::Scalar{110.0 + u(gen) % 80, 100.0 + u(gen) % 50, 50.0 + u(gen) % 30},
                  cv::FILLED);
  return bg;
}

cv::Mat withNoise(const cv::Mat& img, double sd) {
  cv::Mat noise(img.size(), CV_16SC3), wide, out;
  cv::randn(noise, 0, sd);
  img.convertTo(wide, CV_16SC3);
  wide += noise;
  wide.convertTo(out, CV_8UC3);
  return out;
}

double iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter);
}

CondensationConfig smallConfig() {
  CondensationConfig c;
  c.samples = 40;
  return c;
}

}  // namespace

TEST(CondensationConfig, RejectsBadFieldsByName) {
  CondensationConfig c;
  EXPECT_NO_THROW(c.validate());
  c.samples = 0;
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "samples"));
  c = CondensationConfig();
  c.max_stretch = 0.5;
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "max_stretch"));
  c = CondensationConfig();
  c.sigma = 0.0;
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "sigma"));
  c = CondensationConfig();
  c.dynamics.b(0, 0) = std::nan("");
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "dynamics"));
}

TEST(CondensationTracker, RefusesBadImagesAndRegions) {
  CondensationTracker t(smallConfig(), 1);
  const cv::Mat img = clutter(1);
  EXPECT_THROW(t.track(img), std::logic_error);  // before init
  EXPECT_THROW(t.init(cv::Mat(10, 10, CV_8UC1), {0, 0, 5, 5}), std::invalid_argument);
  EXPECT_THROW(t.init(img, {400, 300, 20, 20}), std::invalid_argument);  // outside
  EXPECT_THROW(t.init(img, {10, 10, 2, 2}), std::invalid_argument);      // too small
  t.init(img, {100, 100, 30, 30});
  EXPECT_THROW(t.track(cv::Mat(240, 320, CV_8UC1)), std::invalid_argument);
}

TEST(CondensationTracker, FollowsADiscThatMovesAndChangesColour) {
  const cv::Mat bg = clutter(3);
  CondensationTracker t(smallConfig(), 5);
  cv::setRNGSeed(11);
  double red = 210, green = 70;
  int good = 0, frames = 0;
  for (int k = 0; k < 60; ++k) {
    const double cx = 70 + 3.0 * k, cy = 120 + 35 * std::sin(k / 9.0),
                 r = 20 + 6 * std::sin(k / 15.0);
    red -= 1.2;  // the light dims and greens
    green += 0.8;
    cv::Mat img = bg.clone();
    cv::circle(img, cv::Point(static_cast<int>(std::lround(cx)), static_cast<int>(std::lround(cy))),
               static_cast<int>(std::lround(r)), cv::Scalar(40, green, red), cv::FILLED);
    img = withNoise(img, 6);
    const cv::Rect2d truth(cx - r, cy - r, 2 * r, 2 * r);
    if (k == 0) {
      t.init(img, cv::Rect(truth));
      continue;
    }
    const TrackingResult res = t.track(img);
    ++frames;
    good += !res.lost && iou(res.box, truth) >= 0.6;
    // The samples' magnitudes stay within max_stretch of the measured distribution's.
    const DistributionState m = stateOf(res.distribution);
    for (const auto& s : res.samples)
      for (int d = 3; d < 6; ++d) {
        EXPECT_GE(s[d], m[d] / t.config().max_stretch - 1e-9);
        EXPECT_LE(s[d], m[d] * t.config().max_stretch + 1e-9);
      }
    double total = 0.0;
    for (double w : res.weights) total += w;
    EXPECT_NEAR(total, 1.0, 1e-9);
  }
  EXPECT_GE(good, frames - 2) << good << " of " << frames << " frames tracked";
}

TEST(CondensationTracker, ReportsALossAndReacquiresTheTargetElsewhere) {
  const cv::Mat bg = clutter(5);
  CondensationTracker t(smallConfig(), 2);
  cv::setRNGSeed(3);
  auto frame = [&](bool visible, cv::Point c) {
    cv::Mat img = bg.clone();
    if (visible) cv::circle(img, c, 18, cv::Scalar(30, 60, 220), cv::FILLED);
    return withNoise(img, 5);
  };
  t.init(frame(true, {80, 80}), {62, 62, 36, 36});
  for (int k = 0; k < 3; ++k) EXPECT_FALSE(t.track(frame(true, {80, 80})).lost);
  int lost = 0;
  for (int k = 0; k < 4; ++k) lost += t.track(frame(false, {0, 0})).lost;
  EXPECT_EQ(lost, 4);
  // Back on the far side of the frame: the search widens to the whole image and finds it.
  bool found = false;
  TrackingResult res;
  for (int k = 0; k < 15 && !found; ++k) {
    res = t.track(frame(true, {250, 180}));
    found = !res.lost;
  }
  ASSERT_TRUE(found);
  EXPECT_GE(iou(res.box, {232, 162, 36, 36}), 0.6);
}

TEST(CondensationTracker, AStartingBlobThatLeaksIntoItsSurroundingsKeepsTheRegion) {
  // The target's colour also fills a band around it: the region's ellipse is kept, not the band.
  cv::Mat img(240, 320, CV_8UC3, cv::Scalar(40, 40, 40));
  cv::rectangle(img, cv::Rect(0, 60, 320, 120), cv::Scalar(30, 60, 200), cv::FILLED);
  CondensationTracker t(smallConfig(), 1);
  t.init(withNoise(img, 4), {140, 100, 40, 40});
  const double a = contourArea(t.contour());
  EXPECT_LE(a, 1.5 * M_PI * 20 * 20);
  EXPECT_GE(a, 0.8 * M_PI * 20 * 20);
}
