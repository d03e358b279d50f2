// rostest: condensation_tracker on a simulated tracking sequence, scored against the ground-truth
// box of every frame (IoU >= 0.5 is a success).
#include <geometry_msgs/PolygonStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <opencv2/core.hpp>

#include "adaptive_perception/SetTarget.h"
#include "adaptive_perception/TrackedObject.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "rostest_support.h"

namespace ap = adaptive_perception;

TEST(CondensationTrackerSim, TracksTheTarget) {
  ros::NodeHandle nh, p("~");
  const double min_success = p.param("min_success_rate", 0.9);
  const double min_output = p.param("min_output_fraction", 0.9);
  // The contour of mode condensation has ~contour_points points; that of mode box the box's 4.
  const int contour_points = p.param("contour_points", 48);
  const std::string mode = p.param<std::string>("mode", "condensation");
  std::mutex mutex;
  std::map<ros::Time, cv::Rect2d> truth;
  std::map<ros::Time, ap::TrackedObject> objects;
  const ap::rostest_support::PhaseListener player(nh);
  auto b = nh.subscribe<geometry_msgs::PolygonStamped>(
      "ground_truth/box", 10000, [&](const geometry_msgs::PolygonStampedConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        truth[m->header.stamp] = ap::ros_conv::polygonBox(m->polygon);
      });
  auto c = nh.subscribe<ap::TrackedObject>("tracked_object", 10000,
                                           [&](const ap::TrackedObjectConstPtr& m) {
                                             std::lock_guard<std::mutex> l(mutex);
                                             objects[m->header.stamp] = *m;
                                           });
  ros::AsyncSpinner spinner(2);
  spinner.start();
  // Once tracking runs, a target outside the image is refused in the reply and the track goes on
  // (the success rate below covers every frame after it).
  ASSERT_TRUE(ap::rostest_support::waitUntil(
      [&] {
        std::lock_guard<std::mutex> l(mutex);
        return objects.size() >= 10;
      },
      120.0))
      << "no tracked object";
  ap::SetTarget outside;
  outside.request.roi.x_offset = 5000;
  outside.request.roi.y_offset = 5000;
  outside.request.roi.width = 20;
  outside.request.roi.height = 20;
  ASSERT_TRUE(ros::service::call("condensation_tracker/set_target", outside));
  EXPECT_FALSE(outside.response.success) << outside.response.message;
  EXPECT_NE(outside.response.message.find("outside"), std::string::npos)
      << outside.response.message;
  ASSERT_TRUE(player.waitFor("done", 170.0)) << "the player did not finish";
  std::lock_guard<std::mutex> l(mutex);
  ASSERT_GT(truth.size(), 50u);
  // Every image but the first (the initialisation) should give a tracked object.
  EXPECT_GE(objects.size(), min_output * (truth.size() - 1));
  int scored = 0, success = 0, lost = 0;
  for (const auto& [stamp, o] : objects) {
    const auto t = truth.find(stamp);
    if (t == truth.end()) continue;
    ++scored;
    lost += o.lost;
    const cv::Rect2d box(o.box.x_offset, o.box.y_offset, o.box.width, o.box.height);
    const double inter = (box & t->second).area();
    const double iou = inter / (box.area() + t->second.area() - inter);
    success += !o.lost && iou >= 0.5;
    EXPECT_EQ(o.contour.points.size(), static_cast<std::size_t>(contour_points));
    EXPECT_EQ(o.mode, mode);
  }
  ASSERT_GT(scored, 0);
  const double rate = static_cast<double>(success) / scored;
  std::printf("condensation_tracker_sim: frames=%d success_rate=%.3f lost=%d\n", scored, rate,
              lost);
  EXPECT_GE(rate, min_success);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "condensation_tracker_sim");
  return RUN_ALL_TESTS();
}
