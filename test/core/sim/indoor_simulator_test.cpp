// The indoor-scene simulator: world file, route, sun through windows, determinism, omni ring.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "adaptive_perception/places/histogram.h"
#include "adaptive_perception/sim/indoor_renderer.h"
#include "adaptive_perception/sim/indoor_route.h"

using namespace adaptive_perception;

namespace {
const sim::IndoorWorld& building() {
  static const sim::IndoorWorld w = sim::IndoorWorld::loadYaml(
      std::string(AP_SOURCE_DIR) + "/config/worlds/indoor_building.yaml");
  return w;
}
sim::IndoorLighting sunFrom(double azimuth_rad, double elevation_rad) {
  sim::IndoorLighting l;
  l.kind = sim::IndoorLightingKind::kSunny;
  l.sun = 6.0;
  l.sun_direction = {std::cos(elevation_rad) * std::cos(azimuth_rad),
                     std::cos(elevation_rad) * std::sin(azimuth_rad), std::sin(elevation_rad)};
  return l;
}
}  // namespace

TEST(IndoorWorld, BuildingHasTheIssuesPlacesAndAdjacency) {
  const sim::IndoorWorld& w = building();
  EXPECT_GE(w.places.size(), 10u);
  for (const char* n : {"corridor", "printer_area", "kitchen", "one_person_office",
                        "two_person_office", "entrance_hall", "courtyard", "parking_lot"})
    EXPECT_GE(w.placeIndex(n), 0) << n;
  EXPECT_EQ(w.places[w.placeAt({3, 11})].name, "kitchen");
  EXPECT_EQ(w.placeAt({-5, -5}), -1);
  const auto adj = w.adjacency();
  const int kitchen = w.placeIndex("kitchen"), corridor = w.placeIndex("corridor");
  EXPECT_EQ(adj[kitchen], std::vector<int>{corridor});
  for (size_t a = 0; a < adj.size(); ++a) {
    EXPECT_FALSE(adj[a].empty()) << w.places[a].name << " is not on the route";
    for (int b : adj[a])
      EXPECT_NE(std::find(adj[b].begin(), adj[b].end(), static_cast<int>(a)), adj[b].end());
  }
}

TEST(IndoorWorld, BadFilesNameTheLine) {
  const std::string path = ::testing::TempDir() + "bad_world.yaml";
  std::ofstream(path) << "places:\n  - {name: a, min: [0, 0], max: [1, 1]}\n"
                         "  - {name: b, min: [1, 0], max: [2, 1], floor: marble}\n"
                         "walls: []\nroute: [{xy: [0.5, 0.5]}, {xy: [1.5, 0.5]}]\n";
  try {
    sim::IndoorWorld::loadYaml(path);
    FAIL() << "an unknown floor was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bad_world.yaml:3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("marble"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sim::IndoorWorld::loadYaml(::testing::TempDir() + "missing.yaml"),
               std::runtime_error);
}

TEST(IndoorRoute, DrivesTheWholeRouteInTheComputedTime) {
  const sim::IndoorWorld& w = building();
  sim::IndoorRoute robot(w, 3);
  const double expected = sim::IndoorRoute::duration(w);
  double t = 0.0;
  while (robot.step(0.05)) t += 0.05;
  EXPECT_NEAR(t, expected, 0.2);
  const Eigen::Vector2d end = w.route.back().xy_m;
  EXPECT_NEAR(robot.truePose().x_m, end.x(), 1e-6);
  EXPECT_NEAR(robot.truePose().y_m, end.y(), 1e-6);
  // Odometry drifts, but stays in the building's size.
  const math::SE2 start(w.route[0].xy_m.x(), w.route[0].xy_m.y(), 0.0);
  EXPECT_GT(std::hypot(robot.odomPose().x_m, robot.odomPose().y_m), 0.0);
}

TEST(IndoorRenderer, SunComesThroughTheWindowAndNotThroughWalls) {
  const sim::IndoorRenderer r(building(), {});
  // Conference room: window in the east wall (x = 24, y 9..13, 0.9..2.2 m), sun in the east at 35
  // deg. Floor 1.8 m in: the ray rises 1.26 m at the wall, inside the window.
  const sim::IndoorLighting east = sunFrom(0.0, 35.0 * M_PI / 180.0);
  EXPECT_TRUE(r.sunVisible({22.2, 10.5, 0.01}, east));
  EXPECT_FALSE(r.sunVisible({23.8, 10.5, 0.01}, east));  // 0.14 m at the wall: below the sill
  EXPECT_FALSE(r.sunVisible({20.5, 10.5, 0.01}, east));  // 2.45 m: above the window
  // From the west there is no window: the room is dark.
  EXPECT_FALSE(r.sunVisible({22.2, 10.5, 0.01}, sunFrom(M_PI, 35.0 * M_PI / 180.0)));
  // High sun: the courtyard is lit, the kitchen floor under the ceiling is not.
  const sim::IndoorLighting high = sunFrom(0.3, 80.0 * M_PI / 180.0);
  EXPECT_TRUE(r.sunVisible({21.0, 3.0, 0.01}, high));
  EXPECT_FALSE(r.sunVisible({3.0, 11.0, 0.01}, high));
  // Southern sun at 30 deg over the 1.3 m hedge: the fountain box (0.5 m high, y 1..2.5) shades
  // the grass just north of it, the grass beside it is lit.
  const sim::IndoorLighting south = sunFrom(-M_PI / 2, 30.0 * M_PI / 180.0);
  EXPECT_FALSE(r.sunVisible({22.7, 2.8, 0.01}, south));
  EXPECT_TRUE(r.sunVisible({21.0, 2.8, 0.01}, south));
}

TEST(IndoorRenderer, DeterministicAndLightingChangesTheColours) {
  sim::IndoorCameraConfig cam;
  cam.width_px = 80;
  cam.height_px = 60;
  const sim::IndoorRenderer r(building(), cam);
  const math::SE2 pose(3.5, 11.8, 1.0);  // the kitchen
  math::Rng a(5), b(5);
  const sim::IndoorLighting la = sim::IndoorLighting::sample(sim::IndoorLightingKind::kNight, a);
  const sim::IndoorLighting lb = sim::IndoorLighting::sample(sim::IndoorLightingKind::kNight, b);
  const cv::Mat ia = r.render(pose, la, a), ib = r.render(pose, lb, b);
  EXPECT_EQ(cv::norm(ia, ib, cv::NORM_INF), 0.0);
  math::Rng c(5);
  const cv::Mat sunny =
      r.render(pose, sim::IndoorLighting::sample(sim::IndoorLightingKind::kSunny, c), c);
  // Warm lamps at night against bluish daylight: the blue / red balance differs clearly.
  const cv::Scalar mn = cv::mean(ia), ms = cv::mean(sunny);
  EXPECT_GT(ms[0] / ms[2] - mn[0] / mn[2], 0.1) << "night " << mn << " sunny " << ms;
  // Auto-exposure keeps both images usable.
  for (const cv::Scalar& m : {mn, ms}) {
    const double y = 0.114 * m[0] + 0.587 * m[1] + 0.299 * m[2];
    EXPECT_GT(y, 60.0);
    EXPECT_LT(y, 200.0);
  }
}

TEST(IndoorRenderer, OmniImageIsADonutTheMaskFinds) {
  sim::IndoorCameraConfig cam;
  cam.omni = true;
  const sim::IndoorRenderer r(building(), cam);
  math::Rng rng(1);
  const cv::Mat img =
      r.render(math::SE2(12.0, 11.0, 0.0),
               sim::IndoorLighting::sample(sim::IndoorLightingKind::kCloudy, rng), rng);
  ASSERT_EQ(img.cols, 320);
  ASSERT_EQ(img.rows, 240);
  EXPECT_EQ(img.at<cv::Vec3b>(2, 2), cv::Vec3b(0, 0, 0));  // the black border
  const places::MaskConfig m = places::detectRingMask(img);
  EXPECT_NEAR(m.center_x_px, 160.0, 2.0);
  EXPECT_NEAR(m.center_y_px, 120.0, 2.0);
  EXPECT_NEAR(m.outer_radius_px, cam.outer_radius_px - 2.0, 3.0);
  EXPECT_NEAR(m.inner_radius_px, cam.inner_radius_px + 2.0, 3.0);
}
