// Colour histograms and the elliptical head tracker (papers/001 section 3.2): quantisation, eq 28
// by hand, eq 29, the incremental ellipse histogram against a recomputed one, and tracking a
// moving disc whose colour drifts.
#include "adaptive_perception/tracking/color_histogram.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "adaptive_perception/tracking/ellipse_tracker.h"

using namespace adaptive_perception::tracking;

TEST(Quantizer, BinsOfKnownColours) {
  Quantizer q{ColorSpace::kRgb, 4};
  EXPECT_EQ(q.binOf(cv::Vec3b(0, 0, 0)), 0);
  EXPECT_EQ(q.binOf(cv::Vec3b(255, 255, 255)), 63);
  EXPECT_EQ(q.binOf(cv::Vec3b(0, 0, 255)), 48);  // pure red: r = 3, g = b = 0
  Quantizer o{ColorSpace::kOpponent, 4};
  // Grey: B - G = G - R = 0 -> middle bins (2, 2); R + G + B = 3 x 128 -> 2.
  EXPECT_EQ(o.binOf(cv::Vec3b(128, 128, 128)), (2 * 4 + 2) * 4 + 2);
  // binImage and binOf agree on every pixel, and binOf of the float colour on all but boundaries.
  cv::Mat img(16, 16, CV_8UC3);
  cv::randu(img, 0, 256);
  for (const Quantizer& qq : {q, o}) {
    const cv::Mat bins = qq.binImage(img);
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) EXPECT_EQ(bins.at<int>(y, x), qq.binOf(img.at<cv::Vec3b>(y, x)));
  }
  EXPECT_THROW(parseColorSpace("hsv"), std::invalid_argument);
  EXPECT_EQ(parseColorSpace("rgb"), ColorSpace::kRgb);
}

TEST(Histogram, IntersectionAndModelUpdateByHand) {
  const Histogram c = {2, 0, 3, 5};
  const Histogram m = {1, 4, 3, 0};
  // Eq 28: (min(2,1) + 0 + min(3,3) + 0) / (2 + 0 + 3 + 5) = 4 / 10.
  EXPECT_DOUBLE_EQ(intersection(c, m), 0.4);
  EXPECT_DOUBLE_EQ(intersection(Histogram(4, 0.0f), m), 0.0);
  EXPECT_THROW(intersection(c, Histogram(3, 1.0f)), std::invalid_argument);
  // Eq 29 with a = 0.25 on unit-mass histograms: M = 0.75 m / 8 + 0.25 c / 10.
  Histogram model = m;
  updateModel(&model, c, 0.25);
  const double expect[4] = {0.75 * 1 / 8 + 0.25 * 2 / 10, 0.75 * 4 / 8,
                            0.75 * 3 / 8 + 0.25 * 3 / 10, 0.25 * 5 / 10};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(model[i], expect[i], 1e-6);
  EXPECT_THROW(updateModel(&model, c, 1.5), std::invalid_argument);
}

TEST(EllipseWindow, IncrementalHistogramEqualsRecomputed) {
  cv::Mat img(60, 80, CV_8UC3);
  cv::randu(img, 0, 256);
  const Quantizer q{ColorSpace::kOpponent, 6};
  const cv::Mat bins = q.binImage(img);
  Histogram model(q.size(), 0.0f);
  for (int i = 0; i < q.size(); i += 3) model[i] = 1.0f + i % 7;
  EllipseWindow slid(bins, q.size(), 9.5, 6.2, model), fresh(bins, q.size(), 9.5, 6.2, model);
  // From partly outside the image on the left to partly outside on the right, and on a row
  // that is cut by the top border.
  for (int cy : {30, 3}) {
    slid.place(-5, cy);
    for (int cx = -5; cx < 85; ++cx) {
      if (cx > -5) slid.shiftRight();
      fresh.place(cx, cy);
      ASSERT_EQ(slid.cx(), cx);
      EXPECT_DOUBLE_EQ(slid.pixels(), fresh.pixels());
      for (int i = 0; i < q.size(); ++i) ASSERT_FLOAT_EQ(slid.histogram()[i], fresh.histogram()[i]);
      EXPECT_NEAR(slid.intersection(), fresh.intersection(), 1e-9);
    }
  }
  // The window really is the ellipse: pixel count equals the sum over rows of 2 h + 1.
  fresh.place(40, 30);
  double area = 0;
  for (int h : ellipseRowHalfWidths(9.5, 6.2)) area += 2 * h + 1;
  EXPECT_DOUBLE_EQ(fresh.pixels(), area);
  // And its histogram equals one counted from a drawn mask of the same rows.
  cv::Mat mask = cv::Mat::zeros(bins.size(), CV_8U);
  const auto half = ellipseRowHalfWidths(9.5, 6.2);
  const int ry = static_cast<int>(half.size() / 2);
  for (int dy = -ry; dy <= ry; ++dy)
    for (int dx = -half[dy + ry]; dx <= half[dy + ry]; ++dx) mask.at<uchar>(30 + dy, 40 + dx) = 1;
  const Histogram direct = histogramOf(bins, mask, q.size());
  for (int i = 0; i < q.size(); ++i) EXPECT_FLOAT_EQ(direct[i], fresh.histogram()[i]);
}

namespace {
// Frames (of 59) on which the tracker is within 3 px of a moving disc whose colour drifts.
int framesTracked(double update_rate) {
  std::mt19937 gen(4);
  std::uniform_int_distribution<int> u(0, 255);
  cv::Mat background(240, 320, CV_8UC3, cv::Scalar(0, 0, 0));
  for (int i = 0; i < 60; ++i) {  // grey-blue clutter
    // Drawn last value first, one per statement: the scene this test was written on.
    int v[7];
    for (int k = 6; k >= 0; --k) v[k] = u(gen);
    cv::rectangle(background, cv::Rect(v[0] % 300, v[1] % 220, 10 + v[2] % 40, 10 + v[3] % 40),
                  cv::Scalar(100 + v[4] % 100, 90 + v[5] % 60, 60 + v[6] % 40), cv::FILLED);
  }
  EllipseTrackerConfig cfg;
  cfg.search_radius_px = 8;
  cfg.update_rate = update_rate;
  EllipseTracker tracker(cfg);
  cv::setRNGSeed(7);
  double red = 200, green = 120;
  int good = 0;
  for (int t = 0; t < 60; ++t) {
    cv::Mat img = background.clone();
    const double cx = 80 + 3.0 * t, cy = 120 + 40 * std::sin(t / 10.0);
    red -= 1.0;  // the light dims and warms
    green -= 0.5;
    cv::ellipse(img, cv::Point(static_cast<int>(cx), static_cast<int>(cy)), cv::Size(18, 22), 0, 0,
                360, cv::Scalar(90, green, red), cv::FILLED);
    cv::Mat noise(img.size(), CV_16SC3);  // camera noise spreads each colour over a few bins
    cv::randn(noise, 0, 10);
    cv::Mat noisy;
    img.convertTo(noisy, CV_16SC3);
    noisy += noise;
    noisy.convertTo(img, CV_8UC3);
    if (t == 0) {
      tracker.init(img, {cx, cy, 18, 22});
      continue;
    }
    const EllipseResult r = tracker.track(img);
    good += !r.lost && std::abs(r.ellipse.cx - cx) <= 3.0 && std::abs(r.ellipse.cy - cy) <= 3.0;
  }
  return good;
}
}  // namespace

TEST(EllipseTracker, FollowsAMovingDiscWhoseColourDriftsThanksToTheModelUpdate) {
  EXPECT_EQ(framesTracked(0.1), 59);  // eq 29 on
  EXPECT_LT(framesTracked(0.0), 50);  // a fixed model loses it as the colour drifts
}
