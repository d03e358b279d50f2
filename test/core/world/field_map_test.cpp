#include "adaptive_perception/world/field_map.h"

#include <gtest/gtest.h>

using namespace adaptive_perception::world;

TEST(FieldMap, ShippedYamlLoadsAndMatchesDefaults) {
  const FieldMap map =
      FieldMap::loadYaml(std::string(AP_SOURCE_DIR) + "/config/field_4legged.yaml");
  EXPECT_DOUBLE_EQ(map.dimensions().field_length_m, 5.4);
  EXPECT_EQ(map.cylinders().size(), 4u);
  EXPECT_EQ(map.quads().size(), 4u + 6u);
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
