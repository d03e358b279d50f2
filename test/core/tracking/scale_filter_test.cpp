// tracking::ScaleFilter against scenes zoomed by known factors: the factor found is the one put
// there (within a quarter of a scale step near the trained size, 90% of it 8-9 steps out), the
// training image gives 1, a slow zoom is followed over frames with update(), and bad input is
// refused naming what was wrong.
#include "adaptive_perception/tracking/scale_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "../refusal.h"
#include "texture.h"
#include "adaptive_perception/math/rng.h"

namespace tr = adaptive_perception::tracking;
using adaptive_perception::test_support::refusedNaming;
using adaptive_perception::test_support::texture;

namespace {

/// The scene zoomed by z about (cx, cy).
cv::Mat zoomed(const cv::Mat& image, double z, double cx, double cy) {
  cv::Mat out;
  const cv::Matx23d m(z, 0, cx * (1 - z), 0, z, cy * (1 - z));
  cv::warpAffine(image, out, cv::Mat(m), image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

}  // namespace

TEST(ScaleFilter, FindsTheZoomPutIntoTheScene) {
  const cv::Mat image = texture(320, 240, 3);
  const cv::Point2d centre(160, 120);
  const cv::Size2d target(40, 80);  // narrow and upright, as a person
  tr::ScaleFilter filter;
  filter.init(image, centre, target);
  EXPECT_NEAR(filter.estimate(image, centre, target), 1.0, 0.005);
  const double step = filter.config().scale_step;
  for (double z : {0.93, 0.97, 1.04, 1.1}) {  // within 5 steps of the trained size
    const double found = filter.estimate(zoomed(image, z, centre.x, centre.y), centre, target);
    EXPECT_NEAR(std::log(found), std::log(z), 0.25 * step) << "zoom " << z;
  }
  // Farther out the Hann window over the scales pulls the peak towards 1 (a frame's change is
  // small; the next frame takes the rest): most of the way, never past the truth.
  for (double z : {0.85, 1.2}) {
    const double found = filter.estimate(zoomed(image, z, centre.x, centre.y), centre, target);
    EXPECT_GT(std::log(found) / std::log(z), 0.9) << "zoom " << z;
    EXPECT_LE(std::log(found) / std::log(z), 1.0) << "zoom " << z;
  }
}

// A target that grows by 1% a frame for 40 frames (1.49 in all): each frame's estimate times the
// size so far, the model learnt at each frame, ends within 3% of the truth.
TEST(ScaleFilter, FollowsASlowZoomFrameByFrame) {
  const cv::Mat image = texture(320, 240, 5);
  const cv::Point2d centre(160, 120);
  cv::Size2d size(30, 24);
  tr::ScaleFilter filter;
  filter.init(image, centre, size);
  double truth = 1.0;
  for (int frame = 0; frame < 40; ++frame) {
    truth *= 1.01;
    const cv::Mat now = zoomed(image, truth, centre.x, centre.y);
    const double f = filter.estimate(now, centre, size);
    size = {size.width * f, size.height * f};
    filter.update(now, centre, size);
  }
  EXPECT_NEAR(size.width / 30.0, truth, 0.03 * truth);
  EXPECT_NEAR(size.height / 24.0, truth, 0.03 * truth);
}

TEST(ScaleFilter, RefusesBadInputNamingIt) {
  const cv::Mat image = texture(64, 48, 1);
  tr::ScaleFilterConfig c;
  c.scales = 32;
  EXPECT_TRUE(refusedNaming([&] { tr::ScaleFilter{c}; }, "scales"));
  c = {};
  c.scale_step = 0.0;
  EXPECT_TRUE(refusedNaming([&] { tr::ScaleFilter{c}; }, "scale_step"));
  c = {};
  c.learning_rate = 2.0;
  EXPECT_TRUE(refusedNaming([&] { tr::ScaleFilter{c}; }, "learning_rate"));
  tr::ScaleFilter filter;
  EXPECT_TRUE(refusedNaming([&] { filter.init(cv::Mat(), {10, 10}, {5, 5}); }, "mono8"));
  cv::Mat colour(48, 64, CV_8UC3, cv::Scalar::all(9));
  EXPECT_TRUE(refusedNaming([&] { filter.init(colour, {10, 10}, {5, 5}); }, "mono8"));
  EXPECT_TRUE(refusedNaming([&] { filter.init(image, {10, 10}, {0.5, 5}); }, "pixels a side"));
  EXPECT_TRUE(refusedNaming([&] { filter.init(image, {10, 10}, {NAN, 5}); }, "finite"));
  EXPECT_THROW(filter.estimate(image, {10, 10}, {5, 5}), std::logic_error);
  filter.init(image, {20, 20}, {10, 10});
  EXPECT_TRUE(refusedNaming([&] { filter.estimate(image, {NAN, 5}, {5, 5}); }, "centre"));
  EXPECT_TRUE(refusedNaming([&] { filter.update(image, {5, 5}, {1e300, 5}); }, "pixels a side"));
  EXPECT_TRUE(refusedNaming([&] { filter.estimate(colour, {5, 5}, {5, 5}); }, "mono8"));
  // A target reaching past the image repeats its border: any centre gives a finite factor.
  filter.init(image, {2, 2}, {20, 20});
  const double f = filter.estimate(image, {-30, 70}, {20, 20});
  EXPECT_TRUE(std::isfinite(f) && f > 0.0);
}
