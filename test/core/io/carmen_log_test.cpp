#include "adaptive_perception/io/carmen_log.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace adaptive_perception::io;

TEST(CarmenLog, ParsesEachMessageType) {
  const std::string text =
      "# CARMEN Logfile\n"
      "PARAM robot_front_laser_max 50.0 nohost 0\n"
      "FLASER 3 1.0 2.0 3.0 0.1 0.2 0.3 0.0 0.1 0.2 100.5 host 0.1\n"
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 100.6 host 0.2\n"
      "TRUEPOS 5.0 6.0 1.0 1.0 2.0 0.5 100.7 host 0.3\n"
      "ROBOTLASER1 0 -1.5 3.0 0.75 20.0 0.01 0 5 1 2 3 4 5 0 0.1 0.2 0.3 0.4 0.5 0.6 0.0 0.0 0.5 "
      "0.5 0.2 100.8 host 0.4\n"
      "SYNC foo\n";
  const CarmenLog log = parseCarmenLog(text);
  EXPECT_TRUE(log.issues.empty()) << log.issues.front().what;
  ASSERT_EQ(log.lasers.size(), 2u);
  const CarmenLaser& f = log.lasers[0];
  EXPECT_EQ(f.type, "FLASER");
  EXPECT_EQ(f.ranges_m.size(), 3u);
  EXPECT_NEAR(f.angle_min_rad, -M_PI / 2, 1e-12);
  EXPECT_NEAR(f.angle_increment_rad, M_PI / 2, 1e-12);  // 3 readings over 180 degrees
  EXPECT_DOUBLE_EQ(f.max_range_m, 50.0);                // from PARAM
  EXPECT_DOUBLE_EQ(f.timestamp_s, 100.5);
  EXPECT_DOUBLE_EQ(f.laser_pose.x_m, 0.1);
  EXPECT_DOUBLE_EQ(f.robot_pose.y_m, 0.1);
  const CarmenLaser& r = log.lasers[1];
  EXPECT_EQ(r.type, "ROBOTLASER1");
  EXPECT_EQ(r.ranges_m.size(), 5u);
  EXPECT_DOUBLE_EQ(r.angle_min_rad, -1.5);
  EXPECT_DOUBLE_EQ(r.angle_increment_rad, 0.75);
  EXPECT_DOUBLE_EQ(r.max_range_m, 20.0);
  EXPECT_DOUBLE_EQ(r.laser_pose.x_m, 0.1);
  EXPECT_DOUBLE_EQ(r.robot_pose.x_m, 0.4);
  EXPECT_DOUBLE_EQ(r.timestamp_s, 100.8);
  ASSERT_EQ(log.odometry.size(), 1u);
  EXPECT_DOUBLE_EQ(log.odometry[0].pose.yaw_rad, 0.5);
  EXPECT_DOUBLE_EQ(log.odometry[0].tv_mps, 0.3);
  ASSERT_EQ(log.true_poses.size(), 1u);
  EXPECT_DOUBLE_EQ(log.true_poses[0].true_pose.x_m, 5.0);
  EXPECT_EQ(log.comments, 1);
}

TEST(CarmenLog, ReadingsAtTheMaximumRangeAreNoReturns) {
  // Intel's log has no PARAM: the 81.9 m default, and its laser writes 81.83 for no return.
  const std::string text =
      "FLASER 4 1.0 81.83 81.95 2.0 0 0 0 0 0 0 100.0 host 0.1\n"
      "PARAM robot_front_laser_max 50.0 nohost 0\n"
      "FLASER 3 49.89 49.91 3.0 0 0 0 0 0 0 100.1 host 0.2\n";
  const CarmenLog log = parseCarmenLog(text);
  ASSERT_EQ(log.lasers.size(), 2u);
  const auto& a = log.lasers[0].ranges_m;
  EXPECT_FLOAT_EQ(a[0], 1.0f);
  EXPECT_TRUE(std::isinf(a[1]) && a[1] > 0);  // 81.83 >= 81.9 - 0.1
  EXPECT_TRUE(std::isinf(a[2]) && a[2] > 0);  // beyond the maximum
  EXPECT_FLOAT_EQ(a[3], 2.0f);
  const auto& b = log.lasers[1].ranges_m;
  EXPECT_FLOAT_EQ(b[0], 49.89f);  // just short of 50 - 0.1: a wall
  EXPECT_TRUE(std::isinf(b[1]));
  EXPECT_EQ(log.no_returns, 3);
}

TEST(CarmenLog, ReportsBadLinesWithNumbersAndKeepsGoing) {
  const std::string text =
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 10.0 host 0.2\n"
      "FLASER 180 1.0 2.0\n"                          // 2: truncated
      "ODOM 1.0 two 0.5 0.3 0.1 0.0 11.0 host 0.2\n"  // 3: malformed number
      "WEIRDMSG 1 2 3\n"                              // 4: unknown
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 9.0 host 0.2\n"   // 5: out of order (kept)
      "FLASER -4 1 2\n"                               // 6: bad count
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 12.0 host 0.2\n"
      "ROBOTLASER1 0 -1.5 3.0 0.75 20.0 0.01 0 5 1 2\n"  // 8: truncated
      "ODOM 1.0 2.0 0.5";                                // 9: truncated last line
  CarmenLog log = parseCarmenLog(text);
  std::vector<long> lines;
  for (const auto& i : log.issues) lines.push_back(i.line);
  EXPECT_EQ(lines, (std::vector<long>{2, 3, 4, 5, 6, 8, 9}));
  EXPECT_EQ(log.unknown, 1);
  EXPECT_EQ(log.out_of_order, 1);
  ASSERT_EQ(log.odometry.size(), 3u);
  log.sortByTime();
  EXPECT_DOUBLE_EQ(log.odometry[0].timestamp_s, 9.0);
  EXPECT_DOUBLE_EQ(log.odometry[2].timestamp_s, 12.0);
}

TEST(CarmenLog, RefusesCountsTooLargeForTheLine) {
  // A remission count of 1e44 (found by fuzz_carmen_log: its cast to size_t was undefined).
  const std::string text =
      "ROBOTLASER1 0 -1.5 3.0 0.75 20.0 0.01 0 5 1 2 3 4 5 1e44 0.1 0.2 0.3 0.4 0.5 0.6 0.0 0.0 0.5 "
      "0.5 0.2 100.8 host 0.4\n"
      "ROBOTLASER1 0 -1.5 3.0 0.75 20.0 0.01 0 5 1 2 3 4 5 1e300 0.1 0.2 0.3 0.4 0.5 0.6 0.0 0.0 "
      "0.5 0.5 0.2 100.9 host 0.4\n";
  const CarmenLog log = parseCarmenLog(text);
  ASSERT_EQ(log.issues.size(), 2u);
  EXPECT_EQ(log.issues[0].line, 1);
  EXPECT_NE(log.issues[0].what.find("remission count"), std::string::npos) << log.issues[0].what;
  EXPECT_TRUE(log.lasers.empty());
}

TEST(CarmenLog, ReadsBzip2AndFailsClearlyOnMissingFile) {
  EXPECT_THROW(readCarmenLog("/nonexistent/log.clf"), std::runtime_error);
  const std::string path = ::testing::TempDir() + "/notbz.clf.bz2";
  std::ofstream(path) << "this is not bzip2";
  try {
    readCarmenLog(path);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
  }
  // The project's bundled real log (copied with its licence) reads directly from .bz2.
  const CarmenLog log = readCarmenLog(std::string(AP_SOURCE_DIR) + "/data/laser/mit-csail.clf.bz2");
  EXPECT_EQ(log.lasers.size(), 1988u);
  EXPECT_TRUE(log.issues.empty());
  EXPECT_EQ(log.lasers[0].ranges_m.size(), 361u);
}

TEST(CarmenLog, TellsWhetherTheLasersPosesMove) {
  // FLASER n ranges.. laser_x laser_y laser_th robot_x robot_y robot_th ipc_timestamp host logger
  const std::string still =
      "FLASER 2 1.0 2.0 0 0 0 0 0 0 100.0 host 0.1\n"
      "FLASER 2 1.0 2.0 0 0 0 0 0 0 100.2 host 0.3\n"
      "ODOM 0.5 0.0 0.0 0.3 0.0 0.0 100.1 host 0.2\n";
  EXPECT_FALSE(laserPosesMove(parseCarmenLog(still)));
  const std::string moving =
      "FLASER 2 1.0 2.0 0 0 0 0 0 0 100.0 host 0.1\n"
      "FLASER 2 1.0 2.0 0 0 0 0 0 0.01 100.2 host 0.3\n";
  EXPECT_TRUE(laserPosesMove(parseCarmenLog(moving)));
  EXPECT_FALSE(laserPosesMove(CarmenLog()));
}
