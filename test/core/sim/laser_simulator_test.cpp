#include "adaptive_perception/sim/laser_simulator.h"

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>

#include "adaptive_perception/laser/line_evaluation.h"

using namespace adaptive_perception;

namespace {
sim::LaserWorld box() {
  sim::LaserWorld w;
  w.name = "box";
  w.walls = {{{-2, -2}, {4, -2}}, {{4, -2}, {4, 3}}, {{4, 3}, {-2, 3}}, {{-2, 3}, {-2, -2}}};
  w.route = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  w.laser.range_noise_std_m = 0.0;
  w.laser.dropout_probability = 0.0;
  return w;
}
}  // namespace

TEST(LaserSimulator, NoiselessRangesMatchGeometry) {
  sim::LaserSimulator s(box(), 1);
  std::vector<sim::VisibleWall> visible;
  const laser::LaserScan2D scan = s.scan(&visible);
  // At (0, 0) facing +x with the laser 0.1 m ahead: the beam straight ahead hits x = 4 at 3.9 m.
  const int mid = static_cast<int>(scan.ranges_m.size()) / 2;
  EXPECT_NEAR(scan.bearing(mid), 0.0, 1e-12);
  EXPECT_NEAR(scan.ranges_m[mid], 3.9, 1e-5);
  // Straight left (+90 deg, the last beam of a 180-degree scan): y = 3 at 3 m.
  EXPECT_NEAR(scan.ranges_m.back(), 3.0, 1e-5);
  // The front wall is seen from y = -2 to y = 3 (laser at x = 0.1): in the laser frame x = 3.9.
  bool front = false;
  for (const auto& v : visible)
    if (v.wall == 1) {
      front = true;
      EXPECT_NEAR(v.start_m.x(), 3.9, 1e-6);
      EXPECT_NEAR(v.end_m.x(), 3.9, 1e-6);
    }
  EXPECT_TRUE(front);
}

TEST(LaserSimulator, DeterministicAndDrivesTheRoute) {
  sim::LaserWorld w = box();
  w.laser.range_noise_std_m = 0.01;
  w.laser.dropout_probability = 0.05;
  sim::LaserSimulator a(w, 4), b(w, 4);
  for (int k = 0; k < 200; ++k) {
    a.step(0.05);
    b.step(0.05);
  }
  EXPECT_EQ(a.scan(nullptr).ranges_m, b.scan(nullptr).ranges_m);
  EXPECT_EQ(a.odomPose().x_m, b.odomPose().x_m);
  // 10 s at 0.4 m/s round a 6 m loop: the robot has moved and odometry has drifted from the truth.
  EXPECT_GT(std::hypot(a.truePose().x_m, a.truePose().y_m), 0.3);
  int max_range = 0;
  for (float r : a.scan(nullptr).ranges_m) max_range += r >= w.laser.max_range_m - 1e-6;
  EXPECT_GT(max_range, 0);  // dropouts are reported as max range
}

TEST(LaserSimulator, AStatedRangeMaxAboveTheReachPutsTheNoReturnsBelowIt) {
  // A log with no PARAM line: range_max 81.9 m stated, the laser reaching 3.5 m. The beams
  // straight ahead (3.9 m to the wall) return nothing and are written as 3.5, below range_max,
  // exactly as the laser's reach: what laser::NoReturnFinder looks for.
  sim::LaserWorld w = box();
  w.laser.max_range_m = 3.5;
  w.laser.stated_range_max_m = 81.9;
  sim::LaserSimulator s(w, 1);
  const laser::LaserScan2D scan = s.scan(nullptr);
  EXPECT_DOUBLE_EQ(scan.range_max_m, 81.9);
  const int mid = static_cast<int>(scan.ranges_m.size()) / 2;
  EXPECT_EQ(scan.ranges_m[mid], 3.5f);
  EXPECT_NEAR(scan.ranges_m.back(), 3.0, 1e-5);  // a wall within reach is a wall
  const std::string path = ::testing::TempDir() + "/stated_world.yaml";
  std::ofstream(path) << "name: x\nwalls:\n  - [[0, 0], [1, 0]]\nroute: [[0, 0], [1, 1]]\n"
                         "laser: {max_range_m: 50, stated_range_max_m: 81.9}\n";
  EXPECT_DOUBLE_EQ(sim::LaserWorld::loadYaml(path).laser.stated_range_max_m, 81.9);
  std::ofstream(path) << "name: x\nwalls:\n  - [[0, 0], [1, 0]]\nroute: [[0, 0], [1, 1]]\n"
                         "laser: {max_range_m: 50, stated_range_max_m: 30}\n";
  try {
    sim::LaserWorld::loadYaml(path);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("stated_range_max_m"), std::string::npos) << e.what();
  }
}

TEST(LaserWorld, ShippedWorldsLoadAndBadFilesAreNamed) {
  for (const char* name : {"office", "loop", "rings_and_hall", "rings_and_round_hall_lap"}) {
    const auto w = sim::LaserWorld::loadYaml(std::string(AP_SOURCE_DIR) + "/config/worlds/" + name + ".yaml");
    EXPECT_GT(w.walls.size(), 4u);
    EXPECT_GE(w.route.size(), 4u);
  }
  const std::string path = ::testing::TempDir() + "/bad_world.yaml";
  std::ofstream(path) << "name: x\nwalls:\n  - [[0, 0], [1]]\nroute: [[0, 0], [1, 1]]\n";
  try {
    sim::LaserWorld::loadYaml(path);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3"), std::string::npos) << e.what();
  }
}

TEST(LineEvaluation, HandCountedMatches) {
  laser::LineExtractionConfig cfg;
  // Two true pieces: a wall ahead (x = 3, y -1..1, 40 hits) and a sparse grazing one (not scored).
  const std::vector<laser::TrueWallPiece> truth = {{{3, -1}, {3, 1}, 40}, {{1, 2}, {6, 2}, 8}};
  laser::LineSegment good;
  good.line = {3.0, 0.0, Eigen::Matrix2d::Zero()};
  good.start_m = {3.0, -0.9};
  good.end_m = {3.0, 0.9};
  laser::LineSegment bad = good;  // 0.5 m off the wall
  bad.line.rho_m = 3.5;
  bad.start_m = {3.5, -0.9};
  bad.end_m = {3.5, 0.9};
  const laser::LineScore s = laser::scoreSegments({good, bad}, truth, cfg);
  EXPECT_EQ(s.extracted, 2);
  EXPECT_EQ(s.extracted_matched, 1);
  EXPECT_EQ(s.truth_eligible, 1);  // 8 hits over 5 m: mean spacing 0.71 m > max_gap_m
  EXPECT_EQ(s.truth_matched, 1);
  EXPECT_NEAR(s.meanEndpointError(), 0.1, 1e-12);
  EXPECT_NEAR(s.precision(), 0.5, 1e-12);
}
