// color::whiteBalanceFromPaint on a field drawn here under lights of known colour and brightness:
// the balance found must undo the light (checked against the light's own gains, an independent
// figure), leave a neutral scene as it is, and refuse what is not white paint.
#include "adaptive_perception/color/white_balance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "../refusal.h"
#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/world/color_class.h"

namespace ap = adaptive_perception;
using ap::test_support::refusedNaming;

namespace {

constexpr int kW = 320, kH = 240, kBoundary = 90;

// A carpet below a grey wall with two painted lines (paint RGB 200 everywhere), grass-like noise,
// and a pink and a yellow patch standing on the field (a landmark's bands); seen under a light
// that scales R, G and B by `light`.
cv::Mat drawField(const cv::Vec3d& light_rgb) {
  cv::Mat rgb(kH, kW, CV_32FC3, cv::Scalar(140, 140, 150));
  rgb(cv::Rect(0, kBoundary, kW, kH - kBoundary)).setTo(cv::Scalar(55, 120, 45));
  rgb(cv::Rect(0, 170, kW, 5)).setTo(cv::Scalar(200, 200, 200));
  rgb(cv::Rect(100, kBoundary, 5, kH - kBoundary)).setTo(cv::Scalar(200, 200, 200));
  rgb(cv::Rect(250, 60, 12, 10)).setTo(cv::Scalar(190, 90, 140));
  rgb(cv::Rect(250, 70, 12, 10)).setTo(cv::Scalar(190, 180, 40));
  cv::Mat noise(kH, kW, CV_32FC3);
  cv::RNG rng(3);
  rng.fill(noise, cv::RNG::NORMAL, 0, 4);
  rgb += noise;
  rgb = rgb.mul(cv::Scalar(light_rgb[0], light_rgb[1], light_rgb[2]));
  cv::Mat rgb8, bgr;
  rgb.convertTo(rgb8, CV_8UC3);
  cv::cvtColor(rgb8, bgr, cv::COLOR_RGB2BGR);
  return ap::color::bgrToYuv(bgr);
}

ap::color::WhiteBalance balanceOf(const cv::Mat& yuv, const ap::color::WhiteBalanceConfig& cfg) {
  return ap::color::whiteBalanceFromPaint(
      yuv, ap::color::segmentFieldYuv(yuv, ap::color::FieldSegmentationConfig()), cfg);
}

// Mean absolute difference of two YUV images, over all pixels and channels.
double meanAbsDifference(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat d;
  cv::absdiff(a, b, d);
  const cv::Scalar m = cv::mean(d);
  return (m[0] + m[1] + m[2]) / 3.0;
}

ap::color::WhiteBalanceConfig colourOnly() {
  ap::color::WhiteBalanceConfig cfg;
  cfg.paint_luma = 0.0;
  return cfg;
}

}  // namespace

TEST(WhiteBalance, UndoesATintedLightsGainsUpToTheLuma) {
  const cv::Vec3d light(1.0, 0.85, 0.65);  // a warm lamp
  const ap::color::WhiteBalance wb = balanceOf(drawField(light), colourOnly());
  ASSERT_FALSE(wb.identity);
  EXPECT_GT(wb.paint_pixels, 500);
  // The gains are the light's inverse up to one common factor (the paint keeps its luma).
  const Eigen::Vector3d ratio(wb.gains_rgb[0] * light[0], wb.gains_rgb[1] * light[1],
                              wb.gains_rgb[2] * light[2]);
  EXPECT_NEAR(ratio[1] / ratio[0], 1.0, 0.02);
  EXPECT_NEAR(ratio[2] / ratio[0], 1.0, 0.02);
  // The paint is grey after it, and keeps its luma.
  const Eigen::Vector3d white = wb.apply(wb.white_yuv);
  EXPECT_NEAR(white[1], 128.0, 0.5);
  EXPECT_NEAR(white[2], 128.0, 0.5);
  EXPECT_NEAR(white[0], wb.white_yuv[0], 0.5);
}

TEST(WhiteBalance, TheBalancedImageIsTheSceneUnderAWhiteLight) {
  // Under the warm light and balanced, against the same field under a grey light of the paint's
  // luma (the balance cannot know the light's brightness with paint_luma 0, only its colour).
  const cv::Mat warm = drawField({1.0, 0.85, 0.65});
  const ap::color::WhiteBalance wb = balanceOf(warm, colourOnly());
  const double k = wb.white_yuv[0] / 200.0;  // the warm paint's luma over the neutral paint's
  const cv::Mat neutral = drawField({k, k, k});
  const cv::Mat balanced = wb.apply(warm);
  EXPECT_LT(meanAbsDifference(balanced, neutral), 1.5);
  EXPECT_GT(meanAbsDifference(warm, neutral), 6.0);  // the control: the tint was there
  // The image and one colour are balanced alike.
  const cv::Vec3b p = warm.at<cv::Vec3b>(75, 255);
  const Eigen::Vector3d one = wb.apply(Eigen::Vector3d(p[0], p[1], p[2]));
  const cv::Vec3b q = balanced.at<cv::Vec3b>(75, 255);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(q[ch], one[ch], 0.51) << "channel " << ch;
}

TEST(WhiteBalance, BringsADimmerLightToThePaintsLuma) {
  ap::color::WhiteBalanceConfig cfg;  // the defaults: paint_luma 220
  const cv::Mat bright = drawField({1.0, 1.0, 1.0});
  const cv::Mat dim = drawField({0.6, 0.6, 0.6});
  const ap::color::WhiteBalance a = balanceOf(bright, cfg), b = balanceOf(dim, cfg);
  ASSERT_FALSE(a.identity);
  ASSERT_FALSE(b.identity);
  EXPECT_NEAR(a.apply(a.white_yuv)[0], cfg.paint_luma, 0.5);
  EXPECT_NEAR(b.apply(b.white_yuv)[0], cfg.paint_luma, 0.5);
  // The dim field balanced is the bright one balanced (up to the rounding of the dim image's
  // levels, scaled by 1 / 0.6).
  EXPECT_LT(meanAbsDifference(a.apply(bright), b.apply(dim)), 1.5);
  EXPECT_GT(meanAbsDifference(bright, dim), 10.0);  // the control: 19.8
}

TEST(WhiteBalance, HoldsTheExposureGainWithinItsBound) {
  ap::color::WhiteBalanceConfig cfg;
  cfg.max_exposure_gain = 1.25;
  const ap::color::WhiteBalance wb = balanceOf(drawField({0.4, 0.4, 0.4}), cfg);
  ASSERT_FALSE(wb.identity);
  EXPECT_NEAR(wb.apply(wb.white_yuv)[0], 1.25 * wb.white_yuv[0], 0.5);
}

TEST(WhiteBalance, IsTheChannelsScaledInRgb) {
  // By hand: a dark pixel under gains of 2 doubles its distance from black and from neutral (to
  // 1e-4: color_space.h's rounded BT.601 constants invert each other to about 1e-5).
  ap::color::WhiteBalance wb;
  wb.identity = false;
  wb.gains_rgb = Eigen::Vector3d(2.0, 2.0, 2.0);
  const Eigen::Vector3d dark = wb.apply(Eigen::Vector3d(40, 120, 136));
  EXPECT_NEAR(dark[0], 80.0, 1e-4);
  EXPECT_NEAR(dark[1], 112.0, 1e-4);
  EXPECT_NEAR(dark[2], 144.0, 1e-4);
  // Against the conversions of color_space.h: R, G, B scaled one by one.
  wb.gains_rgb = Eigen::Vector3d(0.8, 1.1, 1.3);
  const Eigen::Vector3d yuv(120, 110, 150);
  const Eigen::Vector3d expected =
      ap::color::rgbToYuv(ap::color::yuvToRgb(yuv).cwiseProduct(wb.gains_rgb));
  EXPECT_LT((wb.apply(yuv) - expected).norm(), 1e-4);
  const cv::Mat image(2, 3, CV_8UC3, cv::Scalar(120, 110, 150));
  const cv::Vec3b q = wb.apply(image).at<cv::Vec3b>(1, 2);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(q[ch], expected[ch], 0.51) << "channel " << ch;
}

TEST(WhiteBalance, ANeutralLightIsLeftAsItIs) {
  const ap::color::WhiteBalance wb = balanceOf(drawField({1.0, 1.0, 1.0}), colourOnly());
  ASSERT_FALSE(wb.identity);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(wb.gains_rgb[ch], 1.0, 0.02) << "channel " << ch;
}

TEST(WhiteBalance, NoPaintOrPaintThatIsNotWhiteGivesNoBalance) {
  const cv::Mat yuv = drawField({1.0, 1.0, 1.0});
  ap::color::FieldSegmentation seg =
      ap::color::segmentFieldYuv(yuv, ap::color::FieldSegmentationConfig());
  // No paint at all.
  ap::color::FieldSegmentation none = seg;
  none.labels.setTo(ap::world::kGreen);
  EXPECT_TRUE(ap::color::whiteBalanceFromPaint(yuv, none, {}).identity);
  // Too few paint pixels.
  ap::color::WhiteBalanceConfig few;
  few.min_paint_pixels = cv::countNonZero(seg.labels == ap::world::kWhite) + 1;  // or fewer
  EXPECT_TRUE(ap::color::whiteBalanceFromPaint(yuv, seg, few).identity);
  // "Paint" of a saturated green (RGB 40, 160, 20): R would need a gain of 2.7 to grey it.
  const cv::Mat green(kH, kW, CV_8UC3, cv::Scalar(20, 160, 40));  // BGR
  ap::color::FieldSegmentation all_paint = seg;
  all_paint.labels.setTo(ap::world::kWhite);
  EXPECT_TRUE(ap::color::whiteBalanceFromPaint(ap::color::bgrToYuv(green), all_paint, {}).identity);
  // The identity copies the image.
  const ap::color::WhiteBalance identity;
  EXPECT_EQ(meanAbsDifference(identity.apply(yuv), yuv), 0.0);
}

TEST(WhiteBalance, BadInputIsRefusedNamingIt) {
  const cv::Mat yuv = drawField({1.0, 1.0, 1.0});
  const ap::color::FieldSegmentation seg =
      ap::color::segmentFieldYuv(yuv, ap::color::FieldSegmentationConfig());
  ap::color::WhiteBalanceConfig cfg;
  cfg.paint_share = 1.5;
  EXPECT_TRUE(refusedNaming([&] { ap::color::whiteBalanceFromPaint(yuv, seg, cfg); },
                            "white_balance_paint_share"));
  cfg = {};
  cfg.max_gain = 0.5;
  EXPECT_TRUE(refusedNaming([&] { ap::color::whiteBalanceFromPaint(yuv, seg, cfg); },
                            "white_balance_max_gain"));
  cv::Mat small;
  cv::resize(yuv, small, {kW / 2, kH / 2});
  EXPECT_THROW(ap::color::whiteBalanceFromPaint(small, seg, {}), std::invalid_argument);
  ap::color::FieldSegmentation wide = seg;
  seg.labels.convertTo(wide.labels, CV_32S);
  EXPECT_TRUE(refusedNaming([&] { ap::color::whiteBalanceFromPaint(yuv, wide, {}); }, "CV_8UC1"));
  EXPECT_THROW(ap::color::WhiteBalance().apply(cv::Mat(4, 4, CV_8UC1)), std::invalid_argument);
}
