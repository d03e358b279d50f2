// The occupancy grid on a room whose every cell is known: a 4 m x 3 m rectangle scanned from
// inside by exact ray casting, so that the walls must come out occupied, the inside free and the
// outside unknown; no-return beams; and the map_server files written, read back and refused
// when malformed.
#include "adaptive_perception/slam/occupancy_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "../scratch_dir.h"

namespace fs = std::filesystem;
using namespace adaptive_perception;

namespace {

// The range from (x, y) along `angle` to the walls of the room [0, 4] x [0, 3].
double rangeInRoom(double x, double y, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  double t = std::numeric_limits<double>::infinity();
  if (c > 1e-12) t = std::min(t, (4.0 - x) / c);
  if (c < -1e-12) t = std::min(t, -x / c);
  if (s > 1e-12) t = std::min(t, (3.0 - y) / s);
  if (s < -1e-12) t = std::min(t, -y / s);
  return t;
}

laser::LaserScan2D scanFrom(const math::SE2& pose) {
  laser::LaserScan2D s;
  s.angle_min_rad = -M_PI;
  s.angle_increment_rad = 2 * M_PI / 720;
  s.range_min_m = 0.05;
  s.range_max_m = 20.0;
  for (int i = 0; i < 720; ++i)
    s.ranges_m.push_back(
        static_cast<float>(rangeInRoom(pose.x_m, pose.y_m, pose.yaw_rad + s.bearing(i))));
  return s;
}

int valueAt(const slam::OccupancyGrid& g, double x, double y) {
  int cx = 0, cy = 0;
  if (!g.cellOf(x, y, &cx, &cy)) return -2;  // outside the grid
  return g.at(cx, cy);
}

}  // namespace

TEST(OccupancyGrid, WallsOccupiedInsideFreeOutsideUnknown) {
  std::vector<laser::LaserScan2D> scans;
  std::vector<math::SE2> poses;
  for (const math::SE2& p :
       {math::SE2(1.0, 1.0, 0.3), math::SE2(3.0, 2.0, -2.0), math::SE2(2.0, 1.5, 1.0)}) {
    scans.push_back(scanFrom(p));
    poses.push_back(p);
  }
  slam::OccupancyGridConfig cfg;
  cfg.resolution_m = 0.05;
  cfg.margin_m = 0.5;
  const slam::OccupancyGrid g = slam::renderOccupancyGrid(scans, poses, cfg);
  // The grid spans the hits (the walls, 0..4 x 0..3) plus the margin.
  EXPECT_NEAR(g.origin_x_m, -0.5, 0.051);
  EXPECT_NEAR(g.origin_y_m, -0.5, 0.051);
  EXPECT_NEAR(g.width * g.resolution_m, 5.0, 0.1);
  EXPECT_NEAR(g.height * g.resolution_m, 4.0, 0.1);
  // Walls: a hit lands within the cell at the wall or the one just inside it.
  int walls = 0, wall_cells = 0;
  for (double x = 0.3; x <= 3.7; x += 0.1)
    for (double y : {0.0, 3.0}) {
      ++wall_cells;
      walls += valueAt(g, x, y) == 100 || valueAt(g, x, y + (y > 0 ? -0.025 : 0.025)) == 100;
    }
  EXPECT_GE(walls, wall_cells - 1);
  // Inside, away from the walls: free. Outside the walls: never seen.
  int inside_free = 0, inside = 0;
  for (double x = 0.2; x <= 3.8; x += 0.1)
    for (double y = 0.2; y <= 2.8; y += 0.1) {
      ++inside;
      inside_free += valueAt(g, x, y) == 0;
    }
  EXPECT_EQ(inside_free, inside);
  for (double x : {-0.3, 4.3})
    for (double y = -0.3; y <= 3.3; y += 0.2) EXPECT_EQ(valueAt(g, x, y), -1) << x << " " << y;
}

TEST(OccupancyGrid, LongReturnsClearAndNoReturnsAreUnused) {
  // Beam 0: a return at 7 m, beyond max_range_m (5 m): its cells up to 5 m are free, no hit.
  // Beam 1: a 2 m return, the only hit. Beam 2 (no return, +inf) points the other way and leaves
  // its side unknown.
  laser::LaserScan2D s;
  s.angle_min_rad = 0.0;
  s.angle_increment_rad = M_PI / 2;  // beam 0 along +x, beam 1 along +y, beam 2 along -x
  s.range_min_m = 0.05;
  s.range_max_m = 8.0;
  s.ranges_m = {7.0f, 2.0f, std::numeric_limits<float>::infinity()};
  slam::OccupancyGridConfig cfg;
  cfg.max_range_m = 5.0;
  cfg.margin_m = 6.0;
  const slam::OccupancyGrid g = slam::renderOccupancyGrid({s}, {math::SE2()}, cfg);
  EXPECT_EQ(valueAt(g, 4.5, 0.0), 0);
  EXPECT_EQ(valueAt(g, 5.5, 0.0), -1) << "beyond max_range_m";
  EXPECT_EQ(valueAt(g, 0.0, 2.0), 100);
  EXPECT_EQ(valueAt(g, 0.0, 1.0), 0);
  EXPECT_EQ(valueAt(g, -1.0, 0.0), -1) << "the no-return is not used";
  int occupied = 0;
  for (std::int8_t v : g.data) occupied += v == 100;
  EXPECT_EQ(occupied, 1) << "only the 2 m return";
  EXPECT_THROW(slam::renderOccupancyGrid({s}, {}, cfg), std::invalid_argument);
  cfg.resolution_m = 0.0;
  EXPECT_THROW(slam::renderOccupancyGrid({s}, {math::SE2()}, cfg), std::invalid_argument);
}

TEST(OccupancyGrid, MapServerFilesRoundTrip) {
  const adaptive_perception::test_support::ScratchDir dir("ap_grid");
  slam::OccupancyGrid g;
  g.resolution_m = 0.1;
  g.origin_x_m = -1.25;
  g.origin_y_m = 2.5;
  g.width = 3;
  g.height = 2;
  g.data = {100, 0, -1, 0, 0, 100};  // row 0 (bottom), then row 1 (top)
  const fs::path yaml = dir.path() / "office.yaml";
  slam::writeMapServerFiles(g, yaml.string());
  // The PGM as map_saver writes it: P5, the top row first, occupied 0 / free 254 / unknown 205.
  std::ifstream pgm(dir.path() / "office.pgm", std::ios::binary);
  std::stringstream ss;
  ss << pgm.rdbuf();
  const std::string bytes = ss.str();
  ASSERT_EQ(bytes.substr(0, 11), "P5\n3 2\n255\n");
  const std::string pixels = bytes.substr(11);
  ASSERT_EQ(pixels.size(), 6u);
  const unsigned char expected[6] = {254, 254, 0, 0, 254, 205};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(static_cast<unsigned char>(pixels[i]), expected[i]) << i;
  std::ifstream y(yaml);
  std::stringstream ys;
  ys << y.rdbuf();
  for (const char* key : {"image: office.pgm", "resolution: 0.1", "origin: [-1.25", "negate: 0",
                          "occupied_thresh: 0.65", "free_thresh: 0.196"})
    EXPECT_NE(ys.str().find(key), std::string::npos) << key << " in\n" << ys.str();
  const slam::OccupancyGrid back = slam::readMapServerFiles(yaml.string());
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_DOUBLE_EQ(back.resolution_m, 0.1);
  EXPECT_DOUBLE_EQ(back.origin_x_m, -1.25);
  EXPECT_DOUBLE_EQ(back.origin_y_m, 2.5);
  EXPECT_EQ(back.data, g.data);
}

TEST(OccupancyGrid, MalformedMapFilesAreNamed) {
  const adaptive_perception::test_support::ScratchDir dir("ap_grid");
  const auto expectError = [&](const std::string& text, const std::string& fragment) {
    const fs::path p = dir.path() / "bad.yaml";
    std::ofstream(p) << text;
    try {
      slam::readMapServerFiles(p.string());
      FAIL() << "accepted:\n" << text;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
    }
  };
  const std::string good_tail = "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  expectError("resolution: 0.05\norigin: [0, 0, 0]\n" + good_tail, "no 'image'");
  expectError("image: nowhere.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n" + good_tail,
              "nowhere.pgm' cannot be read");
  expectError("image: a.pgm\nresolution: 0.05\norigin: [0, 0]\n" + good_tail, "'origin'");
  expectError("image: a.pgm\nresolution: fine\norigin: [0, 0, 0]\n" + good_tail, "wrong type");
  // yaml-cpp reads .inf and .nan as doubles: an infinite cell or a NaN origin is no map.
  expectError("image: a.pgm\nresolution: .inf\norigin: [0, 0, 0]\n" + good_tail, "'resolution'");
  expectError("image: a.pgm\nresolution: 0.05\norigin: [.nan, 0, 0]\n" + good_tail, "'origin'");
  expectError(
      "image: a.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n"
      "occupied_thresh: 0.1\nfree_thresh: 0.5\n",
      "free_thresh < occupied_thresh");
  // An unwritable place is refused naming the file.
  slam::OccupancyGrid g;
  g.width = g.height = 1;
  g.data = {0};
  EXPECT_THROW(slam::writeMapServerFiles(g, (dir.path() / "no" / "such" / "m.yaml").string()),
               std::runtime_error);
}

TEST(OccupancyGrid, KeyframesAfterEnoughMotion) {
  slam::GridKeyframes k(0.1, 0.1);
  const laser::LaserScan2D s = scanFrom(math::SE2(1.0, 1.0, 0.0));
  EXPECT_TRUE(k.add(s, math::SE2(1.0, 1.0, 0.0)));
  EXPECT_FALSE(k.add(s, math::SE2(1.05, 1.0, 0.05)));  // 5 cm, 0.05 rad: not yet
  EXPECT_TRUE(k.add(s, math::SE2(1.1, 1.0, 0.0)));     // 10 cm from the last kept
  EXPECT_TRUE(k.add(s, math::SE2(1.1, 1.0, -0.1)));    // turned 0.1 rad
  EXPECT_EQ(k.size(), 3u);
  EXPECT_THROW(k.add(s, math::SE2(std::nan(""), 0.0, 0.0)), std::invalid_argument);
  k.clear();
  EXPECT_EQ(k.size(), 0u);
}
