// The affine snake (papers/001 section 3.3, Fig 12): it recovers a known affine transform of a
// contour from the transformed shape's edges; the Euler number on shapes with holes; contour
// helpers by hand.
#include "adaptive_perception/tracking/affine_snake.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

using namespace adaptive_perception::tracking;

namespace {
// An L-shaped polygon (not symmetric, so the affine fit is unique).
std::vector<cv::Point> lShape() {
  return {{100, 80}, {160, 80}, {160, 100}, {120, 100}, {120, 150}, {100, 150}};
}
cv::Mat edgesOf(const std::vector<cv::Point>& poly, cv::Size size) {
  cv::Mat filled = cv::Mat::zeros(size, CV_8U), eroded, edge;
  cv::fillPoly(filled, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255));
  cv::erode(filled, eroded, cv::Mat());
  cv::subtract(filled, eroded, edge);
  return edge;
}
}  // namespace

TEST(Contour, HelpersByHand) {
  const Contour square = resampleContour({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, 8);
  ASSERT_EQ(square.size(), 8u);
  EXPECT_DOUBLE_EQ(square[1].x(), 5.0);  // 40 px of perimeter, 5 px apart
  EXPECT_DOUBLE_EQ(square[2].x(), 10.0);
  EXPECT_DOUBLE_EQ(contourArea(square), 100.0);
  EXPECT_DOUBLE_EQ(contourBox(square).width, 10.0);
  Affine2 t;
  t << 2, 0, 5, 0, 1, -3;
  const Contour moved = applyAffine(t, square);
  EXPECT_DOUBLE_EQ(contourArea(moved), 200.0);  // det 2
  EXPECT_DOUBLE_EQ(moved[2].x(), 25.0);
  EXPECT_THROW(resampleContour({{0, 0}, {1, 1}}, 8), std::invalid_argument);
}

TEST(AffineSnake, RecoversAKnownAffineTransform) {
  const Contour start = resampleContour(lShape(), 64);
  // The truth: the L scaled, sheared, rotated a little and moved, by up to 10 px per point (the
  // arms are 20 px thick: a snake starts nearer its own edge than the opposite one, as in
  // tracking where it starts from the predicted contour).
  Affine2 truth;
  truth << 1.08, 0.1, -14, -0.06, 0.97, 8;
  std::vector<cv::Point> moved;
  for (const cv::Point& p : lShape()) {
    const Eigen::Vector2d q = truth.leftCols<2>() * Eigen::Vector2d(p.x, p.y) + truth.col(2);
    moved.emplace_back(static_cast<int>(std::lround(q.x())), static_cast<int>(std::lround(q.y())));
  }
  const cv::Mat edges = edgesOf(moved, {320, 240});
  AffineSnakeConfig cfg;
  cfg.iterations = 60;
  cfg.search_px = 10;
  const AffineSnakeFit fit = fitAffineSnake(start, edges, {0, 0}, cfg);
  EXPECT_GT(fit.on_edge, 0.9);
  // The recovered transform maps the start onto the truth within the pixel rounding.
  const Contour expect = applyAffine(truth, start);
  double worst = 0.0;
  for (size_t i = 0; i < start.size(); ++i)
    worst = std::max(worst, (fit.contour[i] - expect[i]).norm());
  EXPECT_LT(worst, 2.0);
  EXPECT_NEAR(fit.transform(0, 0), 1.08, 0.03);
  EXPECT_NEAR(fit.transform(0, 1), 0.1, 0.03);
  EXPECT_NEAR(fit.transform(1, 1), 0.97, 0.03);
  // With the edges in a sub-image the offset puts them back in place.
  const cv::Rect sub(40, 30, 200, 180);
  const AffineSnakeFit fit2 = fitAffineSnake(start, edges(sub).clone(), sub.tl(), cfg);
  EXPECT_LT((fit2.contour[10] - fit.contour[10]).norm(), 1e-6);
  // No edges: the contour stays.
  const AffineSnakeFit none = fitAffineSnake(start, cv::Mat::zeros(240, 320, CV_8U), {0, 0}, cfg);
  EXPECT_EQ(none.matched, 0);
  EXPECT_LT((none.contour[5] - start[5]).norm(), 1e-12);
  EXPECT_EQ(none.on_edge, 0.0);
}

TEST(EulerNumber, ShapesWithHoles) {
  cv::Mat img = cv::Mat::zeros(60, 80, CV_8U);
  EXPECT_EQ(eulerNumber(img), 0);
  cv::rectangle(img, cv::Rect(5, 5, 20, 20), cv::Scalar(255), cv::FILLED);
  EXPECT_EQ(eulerNumber(img), 1);
  cv::rectangle(img, cv::Rect(10, 10, 4, 4), cv::Scalar(0), cv::FILLED);  // a hole
  EXPECT_EQ(eulerNumber(img), 0);
  cv::rectangle(img, cv::Rect(17, 17, 3, 3), cv::Scalar(0), cv::FILLED);  // another
  EXPECT_EQ(eulerNumber(img), -1);
  cv::circle(img, {60, 40}, 8, cv::Scalar(255), cv::FILLED);  // a second object
  EXPECT_EQ(eulerNumber(img), 0);
  // Objects touching at a corner are one object under 8-connectivity.
  cv::Mat d = cv::Mat::zeros(4, 4, CV_8U);
  d.at<uchar>(1, 1) = d.at<uchar>(2, 2) = 1;
  EXPECT_EQ(eulerNumber(d), 1);
  // Border pixels count (the image is padded with background).
  EXPECT_EQ(eulerNumber(cv::Mat(5, 5, CV_8U, cv::Scalar(1))), 1);
}
