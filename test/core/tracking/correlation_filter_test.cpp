// tracking::CorrelationFilter and its cell features, against cases worked by hand: the orientation
// an edge's gradient falls in, the label recovered on the training window, a known shift and a
// known zoom found where they were put, and what update() does at rates 0 and 1.
#include "adaptive_perception/tracking/correlation_filter.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "../refusal.h"
#include "texture.h"
#include "adaptive_perception/math/rng.h"

namespace tr = adaptive_perception::tracking;
using adaptive_perception::test_support::refusedNaming;
using adaptive_perception::test_support::texture;

namespace {

cv::Mat shifted(const cv::Mat& image, double dx, double dy) {
  cv::Mat out;
  const cv::Matx23d m(1, 0, dx, 0, 1, dy);
  cv::warpAffine(image, out, cv::Mat(m), image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

cv::Point peakOf(const cv::Mat& response, double* value = nullptr) {
  cv::Point at;
  cv::minMaxLoc(response, nullptr, value, nullptr, &at);
  return at;
}

}  // namespace

TEST(CorrelationFilterConfig, RejectsBadFieldsByName) {
  tr::CorrelationFilterConfig c;
  EXPECT_NO_THROW(c.validate());
  c.padding = 1.0;
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "padding"));
  c = {};
  c.lambda = 0.0;
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "lambda"));
  c = {};
  c.orientations = 1;
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "orientations"));
  c = {};
  c.learning_rate = std::nan("");
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "learning_rate"));
}

TEST(GradientCellFeatures, AHorizontalEdgePutsItsEnergyInTheVerticalGradientsBin) {
  // Dark above row 16, bright below: the gradient points down (pi / 2), the centre of bin 4 of 9.
  cv::Mat window(32, 32, CV_32F, cv::Scalar(0.2));
  window.rowRange(16, 32).setTo(0.8);
  const std::vector<cv::Mat> f = tr::gradientCellFeatures(window, 4, 9);
  ASSERT_EQ(f.size(), 10u);
  ASSERT_EQ(f[0].rows, 8);
  ASSERT_EQ(f[0].cols, 8);
  // Rows 15 and 16 hold the edge: cell rows 3 (row 15) and 4 (row 16).
  for (int c = 0; c < 8; ++c) {
    EXPECT_GT(f[4].at<float>(3, c), 0.3f) << "cell column " << c;
    for (int k = 0; k < 9; ++k) {
      if (k == 4) continue;
      EXPECT_NEAR(f[k].at<float>(3, c), 0.0f, 1e-5f) << "bin " << k;
    }
    // Far from the edge nothing moves.
    EXPECT_NEAR(f[4].at<float>(0, c), 0.0f, 1e-5f);
  }
  // The grey channel: each cell's mean minus one half.
  EXPECT_NEAR(f[9].at<float>(0, 0), 0.2f - 0.5f, 1e-5f);
  EXPECT_NEAR(f[9].at<float>(7, 7), 0.8f - 0.5f, 1e-5f);
}

TEST(GradientCellFeatures, AnEdgeAtZeroRadiansIsSharedByTheBinsEitherSide) {
  cv::Mat window(16, 16, CV_32F, cv::Scalar(0.0));
  window.colRange(8, 16).setTo(1.0);  // gradient along +x: angle 0, between bins 8 and 0
  const std::vector<cv::Mat> f = tr::gradientCellFeatures(window, 4, 9);
  EXPECT_GT(f[0].at<float>(1, 1), 0.1f);
  EXPECT_NEAR(f[0].at<float>(1, 1), f[8].at<float>(1, 1), 1e-5f);
}

TEST(CorrelationFilter, RecoversItsLabelOnTheTrainingWindow) {
  const cv::Mat image = texture(320, 240, 1);
  tr::CorrelationFilter filter;
  const cv::Rect2d box(140, 100, 40, 40);
  filter.init(image, box);
  double peak = 0.0;
  const cv::Mat r = filter.response(image, {160, 120}, 1.0);
  EXPECT_EQ(peakOf(r, &peak), cv::Point(filter.cols() / 2, filter.rows() / 2));
  // The label is 1 at its peak; the ridge term takes a little of it.
  EXPECT_GT(peak, 0.9);
  EXPECT_LE(peak, 1.0 + 1e-3);
}

TEST(CorrelationFilter, FindsAKnownShiftInCellsOfTheWindow) {
  const cv::Mat image = texture(320, 240, 2);
  tr::CorrelationFilter filter;
  const cv::Rect2d box(140, 100, 48, 32);  // not square: the grid follows the aspect
  filter.init(image, box);
  const cv::Size2d cell = filter.cellPx(1.0);
  // Move the scene by a whole number of cells right and up; the window stays where it was.
  const int dc = 3, dr = -2;
  const cv::Mat moved = shifted(image, dc * cell.width, dr * cell.height);
  const cv::Mat r = filter.response(moved, {164, 116}, 1.0);
  EXPECT_EQ(peakOf(r), cv::Point(filter.cols() / 2 + dc, filter.rows() / 2 + dr));
}

TEST(CorrelationFilter, PrefersTheScaleAtWhichTheTargetAppears) {
  const cv::Mat image = texture(320, 240, 3);
  tr::CorrelationFilter filter;
  filter.init(image, cv::Rect2d(140, 100, 40, 40));
  // The scene zoomed by 1.25 about the target's centre.
  cv::Mat zoomed;
  const double z = 1.25;
  const cv::Matx23d m(z, 0, 160 * (1 - z), 0, z, 120 * (1 - z));
  cv::warpAffine(image, zoomed, cv::Mat(m), image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  double at_1 = 0.0, at_z = 0.0, at_inverse = 0.0;
  cv::minMaxLoc(filter.response(zoomed, {160, 120}, 1.0), nullptr, &at_1);
  cv::minMaxLoc(filter.response(zoomed, {160, 120}, z), nullptr, &at_z);
  cv::minMaxLoc(filter.response(zoomed, {160, 120}, 1.0 / z), nullptr, &at_inverse);
  EXPECT_GT(at_z, at_1);
  EXPECT_GT(at_z, at_inverse);
  EXPECT_GT(at_z, 0.8);
}

TEST(CorrelationFilter, UpdateAtRateZeroKeepsTheModelAndAtRateOneRetrains) {
  const cv::Mat a = texture(200, 160, 4), b = texture(200, 160, 5);
  const cv::Rect2d box(80, 60, 40, 40);
  const cv::Point2d centre(100, 80);
  tr::CorrelationFilterConfig keep;
  keep.learning_rate = 0.0;
  tr::CorrelationFilter kept(keep), reference;
  kept.init(a, box);
  reference.init(a, box);
  kept.update(b, centre, 1.0);
  EXPECT_LT(
      cv::norm(kept.response(a, centre, 1.0), reference.response(a, centre, 1.0), cv::NORM_INF),
      1e-6);
  tr::CorrelationFilterConfig replace;
  replace.learning_rate = 1.0;
  tr::CorrelationFilter replaced(replace), fresh;
  replaced.init(a, box);
  replaced.update(b, centre, 1.0);
  fresh.init(b, box);
  EXPECT_LT(
      cv::norm(replaced.response(b, centre, 1.0), fresh.response(b, centre, 1.0), cv::NORM_INF),
      1e-5);
}

TEST(CorrelationFilter, AWindowOutsideTheImageIsAnswered) {
  const cv::Mat image = texture(100, 80, 6);
  tr::CorrelationFilter filter;
  filter.init(image, cv::Rect2d(90, 70, 20, 20));  // half outside
  const cv::Mat r = filter.response(image, {-500, -500}, 1.0);
  EXPECT_EQ(r.rows, filter.rows());
  EXPECT_TRUE(cv::checkRange(r));
  EXPECT_THROW(filter.init(image, cv::Rect2d(0, 0, 0, 10)), std::invalid_argument);
}

TEST(CorrelationFilter, ASmallTargetsWindowIsWidenedToMinWindowPx) {
  const cv::Mat image = texture(320, 240, 7);
  const cv::Rect2d small(150, 110, 20, 20);
  tr::CorrelationFilter plain;
  plain.init(image, small);
  tr::CorrelationFilterConfig c;
  c.min_window_px = 80.0;  // 4 times the side: within max_padding (5)
  tr::CorrelationFilter widened(c);
  widened.init(image, small);
  // Same grid of cells, each spanning 80 / 50 = 1.6 times the pixels.
  EXPECT_EQ(widened.cols(), plain.cols());
  EXPECT_NEAR(widened.cellPx(1.0).width / plain.cellPx(1.0).width, 4.0 / 2.5, 1e-9);
  c.min_window_px = 1000.0;  // capped at max_padding
  tr::CorrelationFilter capped(c);
  capped.init(image, small);
  EXPECT_NEAR(capped.cellPx(1.0).width * capped.cols(), 20.0 * c.max_padding, 1e-9);
  c.max_padding = 2.0;  // below padding
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

TEST(CorrelationFilter, ResponseAtReadsTheMapByImagePosition) {
  const cv::Mat image = texture(320, 240, 8);
  tr::CorrelationFilter filter;
  filter.init(image, cv::Rect2d(140, 100, 40, 40));
  const cv::Point2d centre(160, 120);
  const cv::Mat r = filter.response(image, centre, 1.0);
  const cv::Size2d cell = filter.cellPx(1.0);
  const int c = filter.cols() / 2 + 2, row = filter.rows() / 2 - 1;
  const double x = centre.x + 2 * cell.width, y = centre.y - cell.height;
  // On a cell: the map's value; half a cell to the right: the mean of the two neighbours.
  EXPECT_NEAR(filter.responseAt(r, centre, 1.0, x, y), r.at<float>(row, c), 1e-6);
  EXPECT_NEAR(filter.responseAt(r, centre, 1.0, x + 0.5 * cell.width, y),
              0.5 * (r.at<float>(row, c) + r.at<float>(row, c + 1)), 1e-6);
  EXPECT_EQ(filter.responseAt(r, centre, 1.0, centre.x + 1000, y), 0.0);  // outside the map
}
