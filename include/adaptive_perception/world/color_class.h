#pragma once
// The colour classes of the RoboCup four-legged-league field. Class ids are what `camera/labels`
// and the classified images carry (mono8).
#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace adaptive_perception::world {

enum ColorClass : std::uint8_t {
  kGreen = 0,
  kWhite = 1,
  kPink = 2,
  kYellow = 3,
  kCyan = 4,  // the "sky-blue" goal and beacon colour
  kOrange = 5,
  kBackground = 255,  // anything outside the map; never scored
};

constexpr int kNumColorClasses = 6;  // the map colours, ids 0..5

inline const std::array<const char*, kNumColorClasses>& colorClassNames() {
  static const std::array<const char*, kNumColorClasses> names = {"green",  "white", "pink",
                                                                  "yellow", "cyan",  "orange"};
  return names;
}

/// "green" ... "orange", or "background".
inline std::string colorClassName(std::uint8_t id) {
  return id < kNumColorClasses ? colorClassNames()[id] : "background";
}

/// The class for a name ("sky_blue" and "skyblue" are accepted for cyan); nullopt when unknown.
std::optional<ColorClass> parseColorClass(const std::string& name);

/// A display colour (B, G, R) for colourised label images.
std::array<std::uint8_t, 3> colorClassDisplayBgr(std::uint8_t id);

}  // namespace adaptive_perception::world
