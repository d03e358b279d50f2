#pragma once
// Angle helpers. All angles in radians.
#include <cmath>

namespace adaptive_perception::math {

constexpr double kPi = 3.14159265358979323846;

/// Wraps an angle to [-pi, pi).
inline double wrapAngle(double a_rad) {
  a_rad = std::fmod(a_rad + kPi, 2.0 * kPi);
  if (a_rad < 0.0) a_rad += 2.0 * kPi;
  return a_rad - kPi;
}

/// Signed smallest difference a - b, in [-pi, pi).
inline double angleDiff(double a_rad, double b_rad) { return wrapAngle(a_rad - b_rad); }

inline constexpr double degToRad(double deg) { return deg * kPi / 180.0; }
inline constexpr double radToDeg(double rad) { return rad * 180.0 / kPi; }

}  // namespace adaptive_perception::math
