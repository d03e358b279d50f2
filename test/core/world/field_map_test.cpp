#include "adaptive_perception/world/field_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "adaptive_perception/world/label_renderer.h"

using namespace adaptive_perception::world;

namespace {
const std::string kConfig = std::string(AP_SOURCE_DIR) + "/config/";

std::string errorOf(const std::string& yaml) {
  try {
    FieldMap(FieldMap::parseYaml(yaml, "f.yaml"));
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(FieldMap, ShippedYamlLoadsAndMatchesDefaults) {
  const FieldMap map =
      FieldMap::loadYaml(std::string(AP_SOURCE_DIR) + "/config/field_4legged.yaml");
  EXPECT_DOUBLE_EQ(map.dimensions().field_length_m, 5.4);
  EXPECT_EQ(map.cylinders().size(), 4u);
  EXPECT_EQ(map.quads().size(), 4u + 6u);
}

// The shipped four-legged file writes the defaults out: every primitive the renderer sees is the
// same, in the same order (so the label images, the bundled bags and the simulated figures are).
TEST(FieldMap, FourLeggedYamlBuildsTheDefaultPrimitives) {
  const FieldMap a = FieldMap::loadYaml(kConfig + "field_4legged.yaml");
  const FieldMap b;
  ASSERT_EQ(a.groundRects().size(), b.groundRects().size());
  for (size_t i = 0; i < a.groundRects().size(); ++i) {
    const GroundRect &p = a.groundRects()[i], &q = b.groundRects()[i];
    EXPECT_TRUE(p.x0_m == q.x0_m && p.y0_m == q.y0_m && p.x1_m == q.x1_m && p.y1_m == q.y1_m &&
                p.color == q.color)
        << "rect " << i;
  }
  ASSERT_EQ(a.quads().size(), b.quads().size());
  for (size_t i = 0; i < a.quads().size(); ++i) {
    const VerticalQuad &p = a.quads()[i], &q = b.quads()[i];
    EXPECT_TRUE(p.p0_m == q.p0_m && p.p1_m == q.p1_m && p.z0_m == q.z0_m && p.z1_m == q.z1_m &&
                p.color == q.color && p.kind == q.kind)
        << "quad " << i;
  }
  ASSERT_EQ(a.cylinders().size(), b.cylinders().size());
  for (size_t i = 0; i < a.cylinders().size(); ++i) {
    const Cylinder &p = a.cylinders()[i], &q = b.cylinders()[i];
    EXPECT_EQ(p.name, q.name);
    EXPECT_TRUE(p.cx_m == q.cx_m && p.cy_m == q.cy_m && p.radius_m == q.radius_m &&
                p.kind == q.kind && p.bands.size() == q.bands.size());
    for (size_t k = 0; k < p.bands.size() && k < q.bands.size(); ++k)
      EXPECT_TRUE(p.bands[k].z0_m == q.bands[k].z0_m && p.bands[k].z1_m == q.bands[k].z1_m &&
                  p.bands[k].color == q.bands[k].color);
  }
  EXPECT_EQ(b.cylinders()[0].name, "pink_over_yellow");
}

TEST(FieldMap, SplFieldHasPostsMarksAndNoWall) {
  const FieldMap map = FieldMap::loadYaml(kConfig + "field_spl.yaml");
  int walls = 0, goal_quads = 0;
  for (const VerticalQuad& q : map.quads()) {
    walls += q.kind == SurfaceKind::kWall;
    goal_quads += q.kind == SurfaceKind::kGoal;
  }
  EXPECT_EQ(walls, 0);
  EXPECT_EQ(goal_quads, 2);  // the crossbars; the nets are open
  ASSERT_EQ(map.cylinders().size(), 4u);
  for (const Cylinder& c : map.cylinders()) {
    EXPECT_EQ(c.kind, SurfaceKind::kGoal);
    EXPECT_NEAR(std::fabs(c.cy_m), 0.75 + 0.05, 1e-12);  // inner edges 1.5 m apart
    EXPECT_EQ(c.bands.back().color, kWhite);
    EXPECT_DOUBLE_EQ(c.bands.back().z1_m, 0.8);
  }
  // Paint, from the rule book's numbers: penalty mark 1.3 m from the goal line, goal area line
  // 0.6 m in front of it, penalty area line 1.65 m, centre mark, a 0.7 m border, nothing beyond.
  EXPECT_EQ(map.groundColorAt(4.5 - 1.3, 0.0), kWhite);
  EXPECT_EQ(map.groundColorAt(4.5 - 1.3, 0.045), kWhite);  // the cross's arm (0.05 m)
  EXPECT_EQ(map.groundColorAt(4.5 - 1.3, 0.06), kGreen);
  EXPECT_EQ(map.groundColorAt(-(4.5 - 0.6), 1.0), kWhite);
  EXPECT_EQ(map.groundColorAt(-(4.5 - 0.6), 1.2), kGreen);  // beyond the goal area's 1.1 m
  EXPECT_EQ(map.groundColorAt(4.5 - 1.65, 1.9), kWhite);
  EXPECT_EQ(map.groundColorAt(0.04, 0.0), kWhite);  // centre mark
  EXPECT_EQ(map.groundColorAt(0.3, 0.0), kGreen);
  EXPECT_EQ(map.groundColorAt(0.0, 0.75), kWhite);   // centre circle
  EXPECT_EQ(map.groundColorAt(5.15, 3.65), kGreen);  // the border
  EXPECT_EQ(map.groundColorAt(5.25, 0.0), kBackground);
  EXPECT_FALSE(map.isFree(4.7, 0.0, 0.1));  // in the goal
}

// The development set's field: a ray at a landmark's band height meets the band the file lists,
// and a ray at a post's height meets a white goal post.
TEST(FieldMap, SplLandmarksAreHitInTheirColours) {
  const FieldMap map = FieldMap::loadYaml(kConfig + "field_spl_landmarks.yaml");
  EXPECT_EQ(map.cylinders().size(), 4u + 6u);
  LabelRenderer r(map, PinholeCamera::aiboErs7());
  const Eigen::Vector3d from(0.0, 0.0, 0.25);
  auto hitAt = [&](double x, double y, double z) {
    return r.castRay({from.x(), from.y(), z},
                     Eigen::Vector3d(x, y, z) - Eigen::Vector3d(from.x(), from.y(), z));
  };
  const RayHit lower = hitAt(4.675, -3.175, 0.25), upper = hitAt(4.675, -3.175, 0.35),
               base = hitAt(4.675, -3.175, 0.1);
  EXPECT_EQ(lower.kind, SurfaceKind::kBeacon);
  EXPECT_EQ(lower.color, kPink);
  EXPECT_EQ(upper.color, kYellow);
  EXPECT_EQ(base.color, kWhite);
  EXPECT_EQ(hitAt(-4.675, 3.175, 0.35).color, kPink);  // left side: magenta on top
  EXPECT_EQ(hitAt(-4.675, 3.175, 0.25).color, kCyan);
  EXPECT_EQ(hitAt(0.0, 3.175, 0.25).color, kGreen);
  EXPECT_EQ(hitAt(0.0, 3.175, 0.25).kind, SurfaceKind::kBeacon);
  const RayHit post = hitAt(4.5, 0.8, 0.4);
  EXPECT_EQ(post.kind, SurfaceKind::kGoal);
  EXPECT_EQ(post.color, kWhite);
  EXPECT_NEAR(post.range_m, std::hypot(4.5, 0.8) - 0.05, 1e-9);  // through the axis at x 4.5
}

TEST(FieldMap, LandmarkErrorsNameFileLineAndKey) {
  std::string e = errorOf("landmarks:\n  - {x_m: 1, y_m: 1}\n");
  EXPECT_NE(e.find("f.yaml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("no bands"), std::string::npos) << e;
  e = errorOf("landmarks:\n  - {x_m: 1, y_m: 1, bands: []}\n");
  EXPECT_NE(e.find("no bands"), std::string::npos) << e;
  e = errorOf(
      "landmarks:\n  - {x_m: 1, y_m: 1, hieght: 2, bands: [{color: pink, height_m: 0.1}]}\n");
  EXPECT_NE(e.find("f.yaml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("hieght"), std::string::npos) << e;
  e = errorOf(
      "landmarks:\n  - x_m: 1\n    y_m: 1\n    bands:\n      - {color: purple, height_m: 0.1}\n");
  EXPECT_NE(e.find("f.yaml:5"), std::string::npos) << e;
  EXPECT_NE(e.find("purple"), std::string::npos) << e;
  e = errorOf("landmarks:\n  - {x_m: 1, y_m: 1, bands: [{color: pink}]}\n");
  EXPECT_NE(e.find("height_m"), std::string::npos) << e;
  e = errorOf("landmarks:\n  - {x_m: 1, bands: [{color: pink, height_m: 0.1}]}\n");
  EXPECT_NE(e.find("y_m"), std::string::npos) << e;
  e = errorOf("landmarks:\n  - {x_m: 9, y_m: 0, bands: [{color: pink, height_m: 0.1}]}\n");
  EXPECT_NE(e.find("landmarks[0]"), std::string::npos) << e;
  e = errorOf("goal_color_plus_x: none\n");
  EXPECT_NE(e.find("goal_color_plus_x"), std::string::npos) << e;
  e = errorOf("goal_area_depth_m: 0.3\n");
  EXPECT_NE(e.find("goal_area"), std::string::npos) << e;
  e = errorOf("beacon_x_m: 1.35\n");  // the old fixed-beacon keys are gone: a landmark list now
  EXPECT_NE(e.find("unknown key 'beacon_x_m'"), std::string::npos) << e;
  EXPECT_EQ(errorOf("landmarks: []\n"), "");
}

TEST(FieldMap, BeaconColoursFollowTheRules) {
  const FieldMap map;
  int pink_top = 0;
  for (const Cylinder& c : map.cylinders()) {
    ASSERT_EQ(c.bands.size(), 3u);
    EXPECT_EQ(c.bands[0].color, kWhite);
    const ColorClass goal = c.cx_m < 0 ? kYellow : kCyan;
    if (c.cy_m < 0) {  // right side looking from the yellow to the cyan goal
      EXPECT_EQ(c.bands[2].color, kPink);
      EXPECT_EQ(c.bands[1].color, goal);
      ++pink_top;
    } else {
      EXPECT_EQ(c.bands[1].color, kPink);
      EXPECT_EQ(c.bands[2].color, goal);
    }
  }
  EXPECT_EQ(pink_top, 2);
}

TEST(FieldMap, GroundColours) {
  const FieldMap map;
  EXPECT_EQ(map.groundColorAt(0.0, 1.0), kWhite);  // halfway line
  EXPECT_EQ(map.groundColorAt(0.5, 0.5), kGreen);
  EXPECT_EQ(map.groundColorAt(2.69, 0.0), kWhite);  // cyan goal line
  EXPECT_EQ(map.groundColorAt(2.8, 1.0), kGreen);   // carpet margin
  EXPECT_EQ(map.groundColorAt(3.5, 0.0), kBackground);
}

// groundColorAt looks the paint up through a grid of cells; the answer must be the scan over every
// shape in order (first rects, then rings) that it replaces, here written out again as the
// reference.
TEST(FieldMap, GroundColoursThroughTheIndexAreTheFullScans) {
  for (const char* name : {"field_4legged.yaml", "field_spl.yaml", "field_spl_landmarks.yaml"}) {
    const FieldMap map = FieldMap::loadYaml(kConfig + name);
    auto reference = [&](double x, double y) {
      if (!(std::fabs(x) <= map.carpetHalfLength() && std::fabs(y) <= map.carpetHalfWidth()))
        return kBackground;
      for (const auto& g : map.groundRects())
        if (x >= g.x0_m && x <= g.x1_m && y >= g.y0_m && y <= g.y1_m) return g.color;
      for (const auto& g : map.groundRings()) {
        const double r2 = (x - g.cx_m) * (x - g.cx_m) + (y - g.cy_m) * (y - g.cy_m);
        if (r2 >= g.r_inner_m * g.r_inner_m && r2 <= g.r_outer_m * g.r_outer_m) return g.color;
      }
      return kGreen;
    };
    std::vector<std::pair<double, double>> points;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> ux(-map.carpetHalfLength() - 0.2,
                                              map.carpetHalfLength() + 0.2);
    std::uniform_real_distribution<double> uy(-map.carpetHalfWidth() - 0.2,
                                              map.carpetHalfWidth() + 0.2);
    for (int i = 0; i < 200000; ++i) points.emplace_back(ux(rng), uy(rng));
    // Every paint edge exactly, and a hair either side of it: where a cell's list could miss.
    for (const auto& g : map.groundRects())
      for (double x : {g.x0_m, g.x1_m})
        for (double y : {g.y0_m, g.y1_m, 0.5 * (g.y0_m + g.y1_m)})
          for (double e : {-1e-12, 0.0, 1e-12}) {
            points.emplace_back(x + e, y);
            points.emplace_back(0.5 * (g.x0_m + g.x1_m), y + e);
          }
    for (double x : {-map.carpetHalfLength(), map.carpetHalfLength()})
      for (double y : {-map.carpetHalfWidth(), 0.0, map.carpetHalfWidth()})
        points.emplace_back(x, y);
    // On the cells' own edges (0.25 m apart from the carpet's corner), -0, the ring's edges, and
    // far away.
    for (double u = -map.carpetHalfLength(); u <= map.carpetHalfLength(); u += 0.25)
      for (double v = -map.carpetHalfWidth(); v <= map.carpetHalfWidth(); v += 0.25)
        points.emplace_back(u, v);
    for (const auto& g : map.groundRings())
      for (double r : {g.r_inner_m, g.r_outer_m})
        for (double a = 0.0; a < 6.3; a += 0.01)
          points.emplace_back(g.cx_m + r * std::cos(a), g.cy_m + r * std::sin(a));
    for (double big : {1e300, -1e300, HUGE_VAL, -HUGE_VAL}) {
      points.emplace_back(big, 0.0);
      points.emplace_back(0.0, big);
    }
    points.emplace_back(-0.0, -0.0);
    long paint = 0;
    for (const auto& [x, y] : points) {
      const ColorClass want = reference(x, y);
      ASSERT_EQ(map.groundColorAt(x, y), want) << name << " at " << x << ", " << y;
      paint += want == kWhite;
    }
    EXPECT_GT(paint, 1000) << name;  // the points do reach the lines
  }
  const FieldMap map;
  EXPECT_EQ(map.groundColorAt(std::nan(""), 0.0), kBackground);
  EXPECT_EQ(map.groundColorAt(0.0, std::nan("")), kBackground);
}

TEST(FieldMap, FreeSpace) {
  const FieldMap map;
  EXPECT_TRUE(map.isFree(0.0, 0.0, 0.2));
  EXPECT_FALSE(map.isFree(2.9, 0.0, 0.2));     // inside the goal
  EXPECT_FALSE(map.isFree(1.35, -1.95, 0.1));  // a beacon
  EXPECT_FALSE(map.isFree(3.5, 0.0, 0.0));
}

TEST(FieldMap, YamlErrorsNameFileLineAndKey) {
  try {
    FieldMap::parseYaml("field_length_m: 5.4\nfield_widht_m: 3.6\n", "my.yaml");
    FAIL() << "unknown key accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("my.yaml:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("field_widht_m"), std::string::npos) << e.what();
  }
  try {
    FieldMap::parseYaml("goal_width_m: wide\n", "g.yaml");
    FAIL() << "non-number accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("goal_width_m"), std::string::npos) << e.what();
  }
  // Nothing in the file (empty, or a truncated copy that kept only the comments) is refused.
  EXPECT_THROW(FieldMap::parseYaml("", "e.yaml"), std::runtime_error);
  EXPECT_THROW(FieldMap::parseYaml("# Sony four-legged robot league\n# (truncated)\n", "c.yaml"),
               std::runtime_error);
  EXPECT_NO_THROW(FieldMap::parseYaml("field_length_m: 6.0\n", "one_key.yaml"));
  EXPECT_THROW(FieldMap::parseYaml("line_width_m: -1\n", "n.yaml"), std::runtime_error);
  EXPECT_THROW(FieldMap::parseYaml("a: [1,\n", "s.yaml"), std::runtime_error);
  EXPECT_THROW(FieldMap::loadYaml("/nonexistent/field.yaml"), std::runtime_error);
}
