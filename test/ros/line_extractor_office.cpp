// rostest: line_extractor on the bundled office laser bag.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>

#include <map>
#include <mutex>

#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/laser/line_evaluation.h"
#include "adaptive_perception/ros/msg_conversion.h"

using adaptive_perception::LineSegmentArray;
using adaptive_perception::LineSegmentArrayConstPtr;
namespace laser = adaptive_perception::laser;
namespace ros_conv = adaptive_perception::ros_conv;

namespace {

TEST(LineExtractorOffice, PublishesTheWallsInView) {
  ros::NodeHandle nh, p("~");
  const int expected = p.param("expected_scans", 301);
  const double min_precision = p.param("min_precision", 0.95),
               min_recall = p.param("min_recall", 0.95);
  std::mutex mutex;
  std::map<ros::Time, LineSegmentArrayConstPtr> lines, truth;
  int scans = 0;
  auto a = nh.subscribe<LineSegmentArray>("lines", 500, [&](const LineSegmentArrayConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex);
    lines[m->header.stamp] = m;
  });
  auto b = nh.subscribe<LineSegmentArray>("ground_truth/walls", 500,
                                          [&](const LineSegmentArrayConstPtr& m) {
                                            std::lock_guard<std::mutex> l(mutex);
                                            truth[m->header.stamp] = m;
                                          });
  auto c =
      nh.subscribe<sensor_msgs::LaserScan>("scan", 500, [&](const sensor_msgs::LaserScanConstPtr&) {
        std::lock_guard<std::mutex> l(mutex);
        ++scans;
      });
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(60.0);
  while (ros::WallTime::now() < deadline) {
    {
      std::lock_guard<std::mutex> l(mutex);
      if (scans >= expected) break;
    }
    ros::WallDuration(0.1).sleep();
  }
  ros::WallDuration(1.0).sleep();
  std::lock_guard<std::mutex> l(mutex);
  ASSERT_EQ(scans, expected);
  // The node keeps up: (almost) every scan gets its segments, stamped and framed like the scan.
  EXPECT_GE(static_cast<int>(lines.size()), expected - 3);
  laser::LineScore score;
  const laser::LineExtractionConfig cfg;  // the node's defaults (config/line_extractor.yaml)
  for (const auto& [stamp, l] : lines) {
    EXPECT_EQ(l->header.frame_id, "laser");
    auto t = truth.find(stamp);
    ASSERT_NE(t, truth.end()) << "segments with a stamp no scan had";
    score.add(laser::scoreSegments(ros_conv::fromLineSegmentArray(*l),
                                   ros_conv::wallPieces(*t->second), cfg));
  }
  std::printf("line_extractor_office: precision=%.3f recall=%.3f scored_walls=%ld\n",
              score.precision(), score.recall(), score.truth_eligible);
  EXPECT_GT(score.truth_eligible, 500);
  EXPECT_GE(score.precision(), min_precision);
  EXPECT_GE(score.recall(), min_recall);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "line_extractor_office");
  return RUN_ALL_TESTS();
}
