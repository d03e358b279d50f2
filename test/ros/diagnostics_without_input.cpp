// rostest: every node reports on /diagnostics with no input at all and a /clock that never
// ticks (use_sim_time, no clock publisher): each node must publish its status within a few
// seconds of wall time, and its frequency status must not say OK (no input has arrived).
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "rostest_support.h"

namespace ap = adaptive_perception;

TEST(DiagnosticsWithoutInput, EveryNodeReportsThatNothingArrives) {
  ros::NodeHandle nh, p("~");
  std::vector<std::string> nodes;
  ASSERT_TRUE(p.getParam("nodes", nodes)) << "~nodes: the node names to hear from";
  std::mutex mutex;
  std::map<std::string, std::set<int>> levels;  // node -> levels of its statuses
  std::map<std::string, std::set<std::string>> names;
  auto sub = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArrayConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        for (const auto& s : m->status) {
          // diagnostic_updater announces each task as it is added ("Node starting up", OK);
          // what the node checks comes with its updates.
          if (s.message == "Node starting up") continue;
          for (const auto& n : nodes)
            if (s.name.rfind(n + ":", 0) == 0) {
              levels[n].insert(s.level);
              names[n].insert(s.name);
            }
        }
      });
  ros::AsyncSpinner spinner(1);
  spinner.start();
  // The heartbeat is 1 s of wall time; the nodes start within a few seconds under rostest.
  const bool heard = ap::rostest_support::waitUntil(
      [&] {
        std::lock_guard<std::mutex> l(mutex);
        return levels.size() == nodes.size();
      },
      40.0);
  std::lock_guard<std::mutex> l(mutex);
  for (const auto& n : nodes) {
    ASSERT_TRUE(levels.count(n)) << n << " published nothing on /diagnostics without input";
    // At least one of its statuses is WARN or ERROR: no input arrived.
    EXPECT_GT(*levels[n].rbegin(), diagnostic_msgs::DiagnosticStatus::OK)
        << n << " says all is well with no input";
    std::string all;
    for (const auto& s : names[n]) all += s + "; ";
    std::printf("diagnostics_without_input: %s: %s\n", n.c_str(), all.c_str());
  }
  EXPECT_TRUE(heard);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "diagnostics_without_input");
  return RUN_ALL_TESTS();
}
