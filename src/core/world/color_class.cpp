#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::world {

std::optional<ColorClass> parseColorClass(const std::string& name) {
  for (int i = 0; i < kNumColorClasses; ++i)
    if (name == colorClassNames()[i]) return static_cast<ColorClass>(i);
  if (name == "sky_blue" || name == "skyblue" || name == "blue") return kCyan;
  if (name == "background" || name == "unknown") return kBackground;
  return std::nullopt;
}

std::array<std::uint8_t, 3> colorClassDisplayBgr(std::uint8_t id) {
  switch (id) {
    case kGreen:
      return {40, 160, 40};
    case kWhite:
      return {255, 255, 255};
    case kPink:
      return {180, 105, 255};
    case kYellow:
      return {0, 230, 255};
    case kCyan:
      return {230, 200, 40};
    case kOrange:
      return {0, 128, 255};
    default:
      return {40, 40, 40};
  }
}

}  // namespace adaptive_perception::world
