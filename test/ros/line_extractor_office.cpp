// rostest: line_extractor on the bundled office laser bag.
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>

#include <map>

#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/laser/line_evaluation.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "rostest_support.h"

using adaptive_perception::LineSegmentArray;
using adaptive_perception::LineSegmentArrayConstPtr;
namespace laser = adaptive_perception::laser;
namespace ros_conv = adaptive_perception::ros_conv;
namespace rostest_support = adaptive_perception::rostest_support;

namespace {

TEST(LineExtractorOffice, PublishesTheWallsInView) {
  ros::NodeHandle nh, p("~");
  const int expected = p.param("expected_scans", 301);
  const double min_precision = p.param("min_precision", 0.95),
               min_recall = p.param("min_recall", 0.95);
  // The scans first: the test counts them to know the bag has been played, so its subscription
  // must be up before the player's first scan (a run under load once heard 300 of 301).
  rostest_support::TopicRecord<sensor_msgs::LaserScan> scans(nh, "scan", 500);
  rostest_support::TopicRecord<LineSegmentArray> line_record(nh, "lines", 500, true);
  rostest_support::TopicRecord<LineSegmentArray> truth_record(nh, "ground_truth/walls", 500, true);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  rostest_support::waitUntil([&] { return scans.count() >= expected; }, 60.0, 0.1);
  ros::WallDuration(1.0).sleep();
  ASSERT_EQ(scans.count(), expected);
  std::map<ros::Time, LineSegmentArrayConstPtr> lines, truth;
  for (const auto& m : line_record.all()) lines[m->header.stamp] = m;
  for (const auto& m : truth_record.all()) truth[m->header.stamp] = m;
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
