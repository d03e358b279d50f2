// Colour conversions against values worked by hand, histogram binning, and the ring mask.
#include "adaptive_perception/places/histogram.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

using namespace adaptive_perception::places;

namespace {
void expectBands(int space, double r, double g, double b, double b0, double b1, double b2) {
  const auto c = convertPixel(space, r, g, b);
  EXPECT_NEAR(c[0], b0, 1e-9) << spaceName(space) << " band 0 of " << r << "," << g << "," << b;
  EXPECT_NEAR(c[1], b1, 1e-9) << spaceName(space) << " band 1";
  EXPECT_NEAR(c[2], b2, 1e-9) << spaceName(space) << " band 2";
}
}  // namespace

TEST(ColorSpaces, NamesRoundTrip) {
  for (int i = 0; i < kNumSpaces; ++i) EXPECT_EQ(spaceIndex(spaceName(i)), i);
  EXPECT_THROW(spaceIndex("lab"), std::invalid_argument);
  EXPECT_EQ(parseSpaces("hsv,rgb,hsv"), (std::vector<int>{0, 4}));
  EXPECT_EQ(parseSpaces("all").size(), 8u);
}

TEST(ColorSpaces, PrimariesByHand) {
  const int rgb = 0, hsl = 2, hsv = 4, hsi = 6;
  expectBands(rgb, 1, 0.5, 0, 1, 0.5, 0);
  // Red: hue 0; HSV S = 1, V = 1; HSL S = 1, L = 0.5; HSI S = 1 - 0 / (1/3) = 1, I = 1/3.
  expectBands(hsv, 1, 0, 0, 0, 1, 1);
  expectBands(hsl, 1, 0, 0, 0, 1, 0.5);
  expectBands(hsi, 1, 0, 0, 0, 1, 1.0 / 3);
  // Green: hexagonal hue 120 deg = 1/3; HSI: acos(0.5 ((0-1) + 0) / sqrt(1)) = 120 deg.
  expectBands(hsv, 0, 1, 0, 1.0 / 3, 1, 1);
  expectBands(hsi, 0, 1, 0, 1.0 / 3, 1, 1.0 / 3);
  // Blue: 240 deg; the HSI formula gives theta = 120 deg and, with B > G, 360 - 120.
  expectBands(hsv, 0, 0, 1, 2.0 / 3, 1, 1);
  expectBands(hsi, 0, 0, 1, 2.0 / 3, 1, 1.0 / 3);
  // (0.5, 0.25, 0.25): max 0.5, min 0.25. HSV S = 0.5, V = 0.5. HSL L = 0.375, S = 0.25 /
  // (1 - |0.75 - 1|) = 1/3. HSI I = 1/3, S = 1 - 0.25 * 3 = 0.25, hue 0 (num = 0.25 = den).
  expectBands(hsv, 0.5, 0.25, 0.25, 0, 0.5, 0.5);
  expectBands(hsl, 0.5, 0.25, 0.25, 0, 1.0 / 3, 0.375);
  expectBands(hsi, 0.5, 0.25, 0.25, 0, 0.25, 1.0 / 3);
  // Yellow (1, 1, 0): hexagonal hue 60 deg; HSI: num = 0.5 (0 + 1) = 0.5, den = sqrt(0 + 1 * 1)
  // = 1, theta = 60 deg.
  expectBands(hsv, 1, 1, 0, 1.0 / 6, 1, 1);
  expectBands(hsi, 1, 1, 0, 1.0 / 6, 1, 2.0 / 3);
  // Greys: hue and saturation 0.
  expectBands(hsl, 0.3, 0.3, 0.3, 0, 0, 0.3);
  expectBands(hsi, 0, 0, 0, 0, 0, 0);
}

TEST(ColorSpaces, NormalizedVariantsIgnoreIntensity) {
  // eq. (1): (0.1, 0.2, 0.2) and (0.3, 0.6, 0.6) both become (0.2, 0.4, 0.4).
  expectBands(1, 0.1, 0.2, 0.2, 0.2, 0.4, 0.4);
  for (int s = 1; s < kNumSpaces; s += 2) {
    const auto a = convertPixel(s, 0.1, 0.2, 0.2);
    const auto b = convertPixel(s, 0.3, 0.6, 0.6);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 1e-12) << spaceName(s);
  }
  expectBands(1, 0, 0, 0, 1.0 / 3, 1.0 / 3, 1.0 / 3);  // black
}

TEST(Histograms, BinsAndUnitMass) {
  // Four pixels: (R,G,B) = (255,0,0) twice, (0,0,0), (128,128,128). 4 bins: level X -> floor(X /
  // 255 * 4), so 255 -> 3 (clamped), 128 -> 2, 0 -> 0.
  cv::Mat img(2, 2, CV_8UC3);
  img.at<cv::Vec3b>(0, 0) = {0, 0, 255};
  img.at<cv::Vec3b>(0, 1) = {0, 0, 255};
  img.at<cv::Vec3b>(1, 0) = {0, 0, 0};
  img.at<cv::Vec3b>(1, 1) = {128, 128, 128};
  const ImageHistograms h = computeHistograms(img, cv::Mat(), 4, {0, 4});
  ASSERT_TRUE(h.has(0));
  ASSERT_TRUE(h.has(4));
  EXPECT_FALSE(h.has(1));
  const std::vector<float>& rgb = h.spaces[0];
  const std::vector<float> expect_rgb = {0.25, 0, 0.25, 0.5,  // R
                                         0.75, 0, 0.25, 0,    // G
                                         0.75, 0, 0.25, 0};   // B
  for (int i = 0; i < 12; ++i) EXPECT_FLOAT_EQ(rgb[i], expect_rgb[i]) << i;
  // HSV saturation: red 1 (bin 3), black and grey 0 (bin 0).
  EXPECT_FLOAT_EQ(h.spaces[4][4 + 3], 0.5f);
  EXPECT_FLOAT_EQ(h.spaces[4][4 + 0], 0.5f);
  for (int band = 0; band < 3; ++band) {
    double s = 0;
    for (int i = 0; i < 4; ++i) s += h.spaces[4][band * 4 + i];
    EXPECT_NEAR(s, 1.0, 1e-6);
  }
  // 256 bins: an 8-bit level lands in its own bin.
  const ImageHistograms h256 = computeHistograms(img, cv::Mat(), 256, {0});
  EXPECT_FLOAT_EQ(h256.spaces[0][128], 0.25f);
  EXPECT_FLOAT_EQ(h256.spaces[0][255], 0.5f);
}

TEST(Histograms, MaskSelectsPixelsAndEmptyMaskIsAnError) {
  cv::Mat img(2, 2, CV_8UC3, cv::Scalar(0, 0, 0));
  img.at<cv::Vec3b>(0, 0) = {0, 0, 255};
  cv::Mat mask(2, 2, CV_8UC1, cv::Scalar(0));
  mask.at<uchar>(0, 0) = 255;
  const ImageHistograms h = computeHistograms(img, mask, 4, {0});
  EXPECT_FLOAT_EQ(h.spaces[0][3], 1.0f);
  EXPECT_THROW(computeHistograms(img, cv::Mat(2, 2, CV_8UC1, cv::Scalar(0)), 4, {0}),
               std::runtime_error);
  EXPECT_THROW(computeHistograms(cv::Mat(2, 2, CV_8UC1), cv::Mat(), 4, {0}), std::invalid_argument);
}

TEST(Masks, ParseAndDetectRing) {
  EXPECT_EQ(MaskConfig::parse("ring:100,80,20,70").toString(), "ring:100,80,20,70");
  EXPECT_EQ(MaskConfig::parse("auto").kind, MaskConfig::Kind::kAuto);
  EXPECT_THROW(MaskConfig::parse("ring:1,2,3"), std::invalid_argument);
  EXPECT_THROW(MaskConfig::parse("ring:1,2,30,20"), std::invalid_argument);
  EXPECT_THROW(MaskConfig::parse("circle"), std::invalid_argument);

  // A donut like the paper's Fig. 4: lit between radii 20 and 70 around (100, 80), black else.
  cv::Mat img(160, 200, CV_8UC3, cv::Scalar(0, 0, 0));
  cv::circle(img, {100, 80}, 70, cv::Scalar(40, 160, 90), cv::FILLED);
  cv::circle(img, {100, 80}, 20, cv::Scalar(0, 0, 0), cv::FILLED);
  const MaskConfig m = detectRingMask(img);
  EXPECT_NEAR(m.center_x_px, 100.5, 1.0);
  EXPECT_NEAR(m.center_y_px, 80.5, 1.0);
  EXPECT_NEAR(m.inner_radius_px, 22.0, 1.5);
  EXPECT_NEAR(m.outer_radius_px, 68.0, 1.5);
  // The fitted mask keeps only lit pixels: the histogram has no black.
  HistogramConfig cfg;
  cfg.bins = 16;
  cfg.spaces = {0};
  cfg.mask.kind = MaskConfig::Kind::kAuto;
  const ImageHistograms h = computeHistograms(img, cfg);
  EXPECT_FLOAT_EQ(h.spaces[0][0], 0.0f);
  EXPECT_THROW(detectRingMask(cv::Mat(50, 50, CV_8UC3, cv::Scalar(0, 0, 0))), std::runtime_error);
}
