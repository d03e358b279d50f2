// config/enum_names.h: a word table gives parse, name and names, and an error that lists the
// allowed words; checked on a small enumeration and on the project's own tables, each of which
// must parse its every name back to the value it names.
#include "adaptive_perception/config/enum_names.h"

#include <gtest/gtest.h>

#include "../refusal.h"
#include "adaptive_perception/laser/polyline_split.h"
#include "adaptive_perception/math/particle_set.h"
#include "adaptive_perception/sim/indoor_renderer.h"
#include "adaptive_perception/sim/tracking_scene.h"
#include "adaptive_perception/slam/data_association.h"
#include "adaptive_perception/slam/line_ekf_slam.h"
#include "adaptive_perception/tracking/color_histogram.h"

namespace adaptive_perception {
namespace {

enum class Fruit { kApple, kPear, kPlum };

const config::EnumNames<Fruit>& fruits() {
  static const config::EnumNames<Fruit> names(
      "fruit", {{Fruit::kApple, "apple"}, {Fruit::kPear, "pear"}}, {{Fruit::kApple, "malus"}});
  return names;
}

TEST(EnumNames, ParsesNamesAndAliasesAndNamesEachValueOnce) {
  EXPECT_EQ(fruits().parse("apple"), Fruit::kApple);
  EXPECT_EQ(fruits().parse("pear"), Fruit::kPear);
  EXPECT_EQ(fruits().parse("malus"), Fruit::kApple);
  EXPECT_EQ(fruits().name(Fruit::kApple), "apple");  // an alias is never the name
  EXPECT_EQ(fruits().names(), (std::vector<std::string>{"apple", "pear"}));
  EXPECT_EQ(fruits().allowed(), "apple, pear");  // an alias is taken, not offered
}

TEST(EnumNames, RefusesAnUnknownWordListingTheAllowedOnes) {
  EXPECT_EQ(test_support::refusal([] { fruits().parse("Apple"); }),
            "fruit = 'Apple' (allowed: apple, pear)");
  EXPECT_EQ(test_support::refusal([] { fruits().parse(""); }), "fruit = '' (allowed: apple, pear)");
  // A value the table lacks is the program's mistake, not the user's.
  EXPECT_THROW(fruits().name(Fruit::kPlum), std::logic_error);
  EXPECT_THROW(config::EnumNames<Fruit>("fruit", {}), std::logic_error);
}

TEST(EnumNames, TheProjectsTablesReadTheirOwnNamesBack) {
  for (const std::string& s : sim::trackingScenarioNames())
    EXPECT_EQ(sim::trackingScenarioName(sim::parseTrackingScenario(s)), s);
  EXPECT_EQ(sim::trackingScenarioNames().size(), 6u);
  for (const std::string s : {"night", "cloudy", "sunny"})
    EXPECT_EQ(sim::indoorLightingName(sim::parseIndoorLighting(s)), s);
  for (const std::string s : {"standard", "anchor", "external"})
    EXPECT_EQ(slam::variantName(slam::parseVariant(s)), s);
  for (const std::string s : {"nn", "jcbb"})
    EXPECT_EQ(slam::associationName(slam::parseAssociation(s)), s);
  for (const std::string s : {"rgb", "opponent"})
    EXPECT_EQ(tracking::colorSpaceName(tracking::parseColorSpace(s)), s);
  EXPECT_EQ(tracking::parseColorSpace("bgr_opponent"), tracking::ColorSpace::kOpponent);
  EXPECT_EQ(math::parseResamplingScheme("low_variance"), math::ResamplingScheme::kSystematic);
  EXPECT_EQ(laser::parseSplitMethod("hull_tree"), laser::SplitMethod::kHullTree);
  EXPECT_TRUE(test_support::refusedNaming([] { slam::parseVariant("anchored"); },
                                          "variant = 'anchored' (allowed: standard, anchor, "
                                          "external)"));
}

}  // namespace
}  // namespace adaptive_perception
