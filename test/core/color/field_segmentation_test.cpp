// color::segmentField on scenes drawn here, whose field, boundary and lines are known by
// construction: a textured carpet below a grey wall, painted lines, a white robot standing across
// the boundary, an image with no field at all.
#include "adaptive_perception/color/field_segmentation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "../refusal.h"
#include "adaptive_perception/world/color_class.h"

namespace ap = adaptive_perception;
using ap::test_support::refusedNaming;

namespace {

constexpr int kW = 320, kH = 240, kBoundary = 90;

struct Scene {
  cv::Mat bgr;
  cv::Mat lines;  // CV_8UC1, 255 on painted lines
};

// Carpet (BGR about (45, 130, 55), per-pixel noise like grass texture) below row kBoundary, a grey
// wall above; a 4-px line across the field and one down it; a white 50 x 110 px robot standing on
// the field and rising above the boundary.
Scene drawScene() {
  Scene s;
  s.bgr = cv::Mat(kH, kW, CV_8UC3, cv::Scalar(150, 150, 145));
  s.bgr(cv::Rect(0, kBoundary, kW, kH - kBoundary)).setTo(cv::Scalar(45, 130, 55));
  s.lines = cv::Mat::zeros(kH, kW, CV_8UC1);
  cv::rectangle(s.lines, cv::Rect(0, 170, kW, 4), 255, cv::FILLED);
  cv::rectangle(s.lines, cv::Rect(100, kBoundary, 4, kH - kBoundary), 255, cv::FILLED);
  s.bgr.setTo(cv::Scalar(235, 235, 235), s.lines);
  cv::Mat noise(kH, kW, CV_16SC3);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::NORMAL, 0, 10);
  cv::Mat noisy;
  s.bgr.convertTo(noisy, CV_16SC3);
  noisy += noise;
  noisy.convertTo(s.bgr, CV_8UC3);
  // The robot is drawn over the noise: a flat white body.
  cv::rectangle(s.bgr, cv::Rect(200, 60, 50, 110), cv::Scalar(225, 225, 225), cv::FILLED);
  return s;
}

double iou(const cv::Mat& a, const cv::Mat& b) {
  return double(cv::countNonZero(a & b)) / std::max(1, cv::countNonZero(a | b));
}

TEST(FieldSegmentation, FindsTheBoundaryBehindARobotAndThePaintedLines) {
  const Scene s = drawScene();
  const ap::color::FieldSegmentation seg = ap::color::segmentField(s.bgr, {});
  ASSERT_EQ(seg.labels.size(), s.bgr.size());
  // The boundary in every column, the robot's too (it hides the boundary, the hull bridges it).
  int off = 0;
  for (int c = 0; c < kW; ++c)
    if (std::abs(seg.boundary_row.at<int>(0, c) - kBoundary) > 2) ++off;
  EXPECT_EQ(off, 0);
  // Field: everything below the boundary but the lines, the robot's lower body included.
  cv::Mat true_field = cv::Mat::zeros(kH, kW, CV_8UC1);
  true_field(cv::Rect(0, kBoundary, kW, kH - kBoundary)).setTo(255);
  true_field.setTo(0, s.lines);
  EXPECT_GT(iou(seg.labels == ap::world::kGreen, true_field), 0.95);
  // Lines: the two painted lines; the robot is far wider than a line and is not one.
  // Every line pixel found; what else is marked lies within 2 px of a line (the luma is smoothed
  // before the top-hat, so a 4-px line comes out about 5-6 px wide) or on the robot's outline.
  const cv::Mat found = seg.labels == ap::world::kWhite;
  EXPECT_GT(double(cv::countNonZero(found & s.lines)) / cv::countNonZero(s.lines), 0.9);
  cv::Mat near_line;
  cv::dilate(s.lines, near_line, cv::getStructuringElement(cv::MORPH_RECT, {5, 5}));
  const cv::Mat elsewhere = found & ~near_line;
  EXPECT_LT(cv::countNonZero(elsewhere(cv::Rect(0, 0, 190, kH))), 20);
  EXPECT_LT(cv::countNonZero(elsewhere), 0.1 * cv::countNonZero(found));
  const cv::Mat robot_inside = seg.labels(cv::Rect(210, kBoundary, 30, 70));
  EXPECT_EQ(cv::countNonZero(robot_inside == ap::world::kWhite), 0);
  // The carpet's colour is the carpet's (YUV of BGR (45, 130, 55): Y 98, U 102, V 99).
  EXPECT_NEAR(seg.carpet_mean_yuv[0], 98.0, 5.0);
  EXPECT_LT(seg.carpet_mean_yuv[1], 115.0);
  EXPECT_LT(seg.carpet_mean_yuv[2], 115.0);
}

// YUV (BT.601 full range) with grass-like noise of `sd` levels on every channel.
cv::Mat noisyYuv(const cv::Mat& yuv, double sd, int seed) {
  cv::Mat noise(yuv.size(), CV_16SC3), out;
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0, sd);
  yuv.convertTo(out, CV_16SC3);
  out += noise;
  out.convertTo(out, CV_8UC3);
  return out;
}

TEST(FieldSegmentation, AWallOfTheCarpetsChromaInTheLowerHalfIsNotField) {
  // A dark carpet (Y 50) below row 150 and, between rows 100 and 150, a pale wall of the same
  // chroma but three times as bright (a goal's back wall under a green-tinted light); grey above.
  // The wall fills a quarter of the image's lower half, where the carpet's seed is taken: the
  // seed's central half of the luma leaves out most of it, and EM separates the rest.
  cv::Mat yuv(kH, kW, CV_8UC3, cv::Scalar(180, 128, 128));
  yuv(cv::Rect(0, 100, kW, 50)).setTo(cv::Scalar(150, 110, 122));
  yuv(cv::Rect(0, 150, kW, kH - 150)).setTo(cv::Scalar(50, 110, 122));
  const auto seg = ap::color::segmentFieldYuv(noisyYuv(yuv, 3.0, 11), {});
  int off = 0;
  for (int c = 0; c < kW; ++c)
    if (std::abs(seg.boundary_row.at<int>(0, c) - 150) > 2) ++off;
  EXPECT_EQ(off, 0);
  EXPECT_NEAR(seg.carpet_mean_yuv[0], 50.0, 5.0);
}

TEST(FieldSegmentation, FindsPaintMoreChromaticThanADarkCarpet) {
  // Under a warm light white paint takes the light's tint in proportion to its brightness: here
  // its chroma (about 26 levels) exceeds the dark green carpet's (about 20), yet relative to its
  // luma it is far paler (0.14 against 0.39).
  cv::Mat yuv(kH, kW, CV_8UC3, cv::Scalar(180, 128, 128));
  yuv(cv::Rect(0, kBoundary, kW, kH - kBoundary)).setTo(cv::Scalar(50, 110, 120));
  cv::Mat lines = cv::Mat::zeros(kH, kW, CV_8UC1);
  cv::rectangle(lines, cv::Rect(0, 170, kW, 4), 255, cv::FILLED);
  yuv.setTo(cv::Scalar(185, 108, 145), lines);
  const auto seg = ap::color::segmentFieldYuv(noisyYuv(yuv, 3.0, 12), {});
  const cv::Mat found = seg.labels == ap::world::kWhite;
  EXPECT_GT(double(cv::countNonZero(found & lines)) / cv::countNonZero(lines), 0.9);
  // And nothing else: within 3 px of the line (the smoothing widens a line of this contrast, 135
  // levels, by up to 3 px) or not at all.
  cv::Mat near_line;
  cv::dilate(lines, near_line, cv::getStructuringElement(cv::MORPH_RECT, {7, 7}));
  EXPECT_LT(cv::countNonZero(found & ~near_line), 20);
}

TEST(FieldSegmentation, ABallOnTheCarpetIsNotALine) {
  // A white ball of radius 10 px with five black patches on the carpet, beside a painted line:
  // between its patches the ball is as thin and bright as paint, but its patches are dark.
  Scene s = drawScene();
  const cv::Point centre(60, 130);
  cv::circle(s.bgr, centre, 10, cv::Scalar(235, 235, 235), cv::FILLED);
  for (int k = 0; k < 5; ++k) {
    const double a = 2.0 * M_PI * k / 5.0;
    const cv::Point patch(std::lround(6 * std::cos(a)), std::lround(6 * std::sin(a)));
    cv::circle(s.bgr, centre + patch, 3, cv::Scalar(20, 20, 20), cv::FILLED);
  }
  const auto seg = ap::color::segmentField(s.bgr, {});
  cv::Mat ball = cv::Mat::zeros(kH, kW, CV_8UC1);
  cv::circle(ball, centre, 13, 255, cv::FILLED);
  EXPECT_EQ(cv::countNonZero((seg.labels == ap::world::kWhite) & ball), 0);
  // The painted lines are still found.
  const cv::Mat found = seg.labels == ap::world::kWhite;
  EXPECT_GT(double(cv::countNonZero(found & s.lines)) / cv::countNonZero(s.lines), 0.9);
}

TEST(FieldSegmentation, BrightBlobsAreNotLinesButAShortDashIs) {
  // Plain bright blobs on the carpet, narrower than the top-hat's window (so thin and bright as
  // paint is) and larger than the smallest stroke kept (line_min_area_share: 15 px here), without
  // dark parts beside them: a disc of radius 5 px (a sunlit tuft, a ball's white side; length^2 /
  // area 1.3) and a 7 x 7 px square (1.3). And a dash of paint 28 x 4 px (9.3: a line cut short by
  // the image's edge or by a robot standing on it).
  Scene s = drawScene();
  const cv::Point disc(40, 130);
  const cv::Rect square(150, 200, 7, 7), dash(130, 120, 28, 4);
  cv::circle(s.bgr, disc, 5, cv::Scalar(235, 235, 235), cv::FILLED);
  cv::rectangle(s.bgr, square, cv::Scalar(235, 235, 235), cv::FILLED);
  cv::rectangle(s.bgr, dash, cv::Scalar(235, 235, 235), cv::FILLED);
  cv::Mat blobs = cv::Mat::zeros(kH, kW, CV_8UC1);
  cv::circle(blobs, disc, 8, 255, cv::FILLED);
  cv::rectangle(blobs, cv::Rect(147, 197, 13, 13), 255, cv::FILLED);
  cv::Mat dash_mask = cv::Mat::zeros(kH, kW, CV_8UC1);
  dash_mask(dash).setTo(255);
  const auto seg = ap::color::segmentField(s.bgr, {});
  const cv::Mat found = seg.labels == ap::world::kWhite;
  EXPECT_EQ(cv::countNonZero(found & blobs), 0);
  EXPECT_GT(double(cv::countNonZero(found & dash_mask)) / cv::countNonZero(dash_mask), 0.9);
  EXPECT_GT(double(cv::countNonZero(found & s.lines)) / cv::countNonZero(s.lines), 0.9);
  // Without the elongation check the blobs are taken for paint: what the check does.
  ap::color::FieldSegmentationConfig off;
  off.line_min_elongation = 0.0;
  const auto unchecked = ap::color::segmentField(s.bgr, off);
  EXPECT_GT(cv::countNonZero((unchecked.labels == ap::world::kWhite) & blobs), 80);
}

TEST(FieldSegmentation, TheRobotsOwnArmAtTheBottomDoesNotHideTheCarpetAboveIt) {
  // The robot's own arm (grey-blue) fills the bottom 100 rows of the image's left 80 columns,
  // taller than the 50 rows of carpet above it there: the whole column holds more arm than
  // carpet, yet the field's boundary is where the carpet begins.
  Scene s = drawScene();
  s.bgr(cv::Rect(0, 140, 80, kH - 140)).setTo(cv::Scalar(150, 110, 90));
  const auto seg = ap::color::segmentField(s.bgr, {});
  int off = 0;
  for (int c = 0; c < 80; ++c)
    if (std::abs(seg.boundary_row.at<int>(0, c) - kBoundary) > 2) ++off;
  EXPECT_EQ(off, 0);
}


// Against a side the narrow-peak window (33 px of 320) is cut off. The strips below are 24 px
// wide: narrower than the window, wider than its half, so the closing alone keeps every one.
int columnsOff(const ap::color::FieldSegmentation& seg, int from, int to, int row) {
  int off = 0;
  for (int c = from; c < to; ++c)
    if (std::abs(seg.boundary_row.at<int>(0, c) - row) > 2) ++off;
  return off;
}

TEST(FieldSegmentation, ACarpetColouredStripUpTheImagesSideIsNotField) {
  // A backlit hall's dark interior at the image's left edge, of the carpet's colour from the
  // image's top down to the field: the boundary stays at the field's edge in every column (the
  // hull drawn to the strip's top would run diagonally across the image).
  Scene s = drawScene();
  s.bgr(cv::Rect(0, 0, 24, kBoundary)).setTo(cv::Scalar(45, 130, 55));
  EXPECT_EQ(columnsOff(ap::color::segmentField(s.bgr, {}), 0, kW, kBoundary), 0);
}

TEST(FieldSegmentation, AStripRisingMoreSteeplyThan45DegreesAtASideIsHeldDown) {
  // 40 rows above the field in 24 columns: more than the window's 32 rows.
  Scene s = drawScene();
  s.bgr(cv::Rect(0, kBoundary - 40, 24, 40)).setTo(cv::Scalar(45, 130, 55));
  EXPECT_EQ(columnsOff(ap::color::segmentField(s.bgr, {}), 0, kW, kBoundary), 0);
}

TEST(FieldSegmentation, AStripOfFieldBetweenAPlayerAndTheSideStaysField) {
  // A dark-clad player (legs down to row 200) stands 24 px from the image's right edge, and the
  // field's edge beyond the player stands 10 rows higher than anywhere else in view (it rises
  // towards the right): less steep than 45 degrees, so the strip stays field at its height.
  Scene s = drawScene();
  s.bgr(cv::Rect(kW - 24 - 30, 40, 30, 160)).setTo(cv::Scalar(90, 40, 30));
  s.bgr(cv::Rect(kW - 24, kBoundary - 10, 24, 10)).setTo(cv::Scalar(45, 130, 55));
  EXPECT_EQ(columnsOff(ap::color::segmentField(s.bgr, {}), kW - 24, kW, kBoundary - 10), 0);
}

TEST(FieldSegmentation, ARobotNearTheCameraHidingTheMiddleDoesNotHoldTheSidesDown) {
  // A dark robot close to the camera covers every column but the outer 32 on each side, from
  // row 20 down to row 200: the field's edge is seen only in the two side strips, and both stay
  // at it (the hull bridges the robot there).
  Scene s = drawScene();
  s.bgr(cv::Rect(32, 20, kW - 64, 180)).setTo(cv::Scalar(90, 40, 30));
  const auto seg = ap::color::segmentField(s.bgr, {});
  EXPECT_EQ(columnsOff(seg, 0, 32, kBoundary), 0);
  EXPECT_EQ(columnsOff(seg, kW - 32, kW, kBoundary), 0);
}

TEST(FieldSegmentation, AnImageWithoutGreenHasNoField) {
  cv::Mat grey(120, 160, CV_8UC3, cv::Scalar(120, 120, 120));
  cv::rectangle(grey, cv::Rect(0, 60, 160, 60), cv::Scalar(40, 60, 200), cv::FILLED);  // red floor
  const auto seg = ap::color::segmentField(grey, {});
  EXPECT_EQ(cv::countNonZero(seg.labels != ap::world::kBackground), 0);
}

TEST(FieldSegmentation, IsDeterministic) {
  const Scene s = drawScene();
  const auto a = ap::color::segmentField(s.bgr, {}), b = ap::color::segmentField(s.bgr, {});
  EXPECT_EQ(cv::countNonZero(a.labels != b.labels), 0);
}

TEST(FieldSegmentation, BadInputIsRefusedNamingIt) {
  EXPECT_TRUE(refusedNaming([] { ap::color::segmentField(cv::Mat(), {}); }, "BGR8"));
  EXPECT_TRUE(refusedNaming([] { ap::color::segmentField(cv::Mat(4, 4, CV_8UC1), {}); }, "BGR8"));
  ap::color::FieldSegmentationConfig cfg;
  cfg.line_window_share = 0.0;
  EXPECT_TRUE(refusedNaming([&] { cfg.validate(); }, "line_window_share"));
}

}  // namespace
