// tracking::scoreTrack against cases worked out by hand.
#include "adaptive_perception/tracking/benchmark_metrics.h"

#include <gtest/gtest.h>

namespace tr = adaptive_perception::tracking;

TEST(BenchmarkMetrics, IouAndCentreErrorOfSimpleBoxes) {
  EXPECT_DOUBLE_EQ(tr::boxIou({0, 0, 10, 10}, {0, 0, 10, 5}), 0.5);
  EXPECT_DOUBLE_EQ(tr::boxIou({0, 0, 10, 10}, {5, 0, 10, 10}), 50.0 / 150.0);
  EXPECT_DOUBLE_EQ(tr::boxIou({0, 0, 10, 10}, {20, 20, 5, 5}), 0.0);
  EXPECT_DOUBLE_EQ(tr::centreError({0, 0, 10, 10}, {3, 4, 10, 10}), 5.0);
}

TEST(BenchmarkMetrics, APerfectTrackScoresOneButAtTheLastThreshold) {
  const std::vector<std::optional<cv::Rect2d>> truth = {cv::Rect2d(0, 0, 10, 10),
                                                        cv::Rect2d(5, 5, 10, 10)};
  const tr::TrackScores s = tr::scoreTrack(truth, truth);
  EXPECT_EQ(s.frames_scored, 2);
  EXPECT_DOUBLE_EQ(s.success_rate, 1.0);
  EXPECT_DOUBLE_EQ(s.precision_20px, 1.0);
  EXPECT_DOUBLE_EQ(s.auc, 20.0 / 21.0);  // IoU 1 is not > 1
}

TEST(BenchmarkMetrics, LostFramesAndFramesWithoutTruth) {
  // Frame 0: IoU exactly 0.5, centre 2.5 px off. Frame 1: lost. Frame 2: no truth (not scored).
  const std::vector<std::optional<cv::Rect2d>> boxes = {cv::Rect2d(0, 0, 10, 5), std::nullopt,
                                                        cv::Rect2d(0, 0, 1, 1)};
  const std::vector<std::optional<cv::Rect2d>> truth = {cv::Rect2d(0, 0, 10, 10),
                                                        cv::Rect2d(0, 0, 10, 10), std::nullopt};
  const tr::TrackScores s = tr::scoreTrack(boxes, truth);
  EXPECT_EQ(s.frames_scored, 2);
  EXPECT_DOUBLE_EQ(s.success_rate, 0.5);
  EXPECT_DOUBLE_EQ(s.mean_iou, 0.25);
  // IoU 0.5 exceeds the thresholds 0 .. 0.45 (10 of 21) in one frame of two.
  EXPECT_DOUBLE_EQ(s.auc, 10 * 0.5 / 21.0);
  EXPECT_DOUBLE_EQ(s.success_curve[9], 0.5);
  EXPECT_DOUBLE_EQ(s.success_curve[10], 0.0);
  EXPECT_DOUBLE_EQ(s.precision_20px, 0.5);
  EXPECT_DOUBLE_EQ(s.precision_curve[2], 0.0);  // 2.5 px > 2
  EXPECT_DOUBLE_EQ(s.precision_curve[3], 0.5);
  EXPECT_THROW(tr::scoreTrack(boxes, {truth[0]}), std::invalid_argument);
}
