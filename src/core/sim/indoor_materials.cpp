// The indoor renderer's materials: the albedo of the floors and walls at a point, from the place's
// and the wall's procedural textures (procedural_texture.h).
#include <algorithm>
#include <cmath>

#include "adaptive_perception/sim/indoor_renderer.h"
#include "procedural_texture.h"

namespace adaptive_perception::sim {

using texture::hash01;
using texture::randomColour;
using texture::valueNoise;

Eigen::Vector3d IndoorRenderer::floorAlbedo(int place, double x, double y) const {
  if (place < 0) return world_.ground_rgb * (0.8 + 0.4 * valueNoise(x * 4, y * 4, 7));
  const PlaceStyle& s = world_.places[place].style;
  const Eigen::Vector3d& c = s.floor_rgb;
  switch (s.floor_pattern) {
    case FloorPattern::kCarpet:
      return c * (0.8 + 0.25 * valueNoise(x * 20, y * 20, place) +
                  0.1 * valueNoise(x * 2, y * 2, place + 50));
    case FloorPattern::kTiles: {
      const double gx = x * 2.0 - std::floor(x * 2.0), gy = y * 2.0 - std::floor(y * 2.0);
      if (gx < 0.03 || gy < 0.03) return c * 0.55;  // grout
      const bool odd = (static_cast<std::int64_t>(std::floor(x * 2)) +
                        static_cast<std::int64_t>(std::floor(y * 2))) %
                           2 !=
                       0;
      return c * (odd ? 0.82 : 1.0) * (0.95 + 0.1 * valueNoise(x * 9, y * 9, place));
    }
    case FloorPattern::kWood: {
      const auto plank = static_cast<std::int64_t>(std::floor(y / 0.15));
      const double shade = 0.75 + 0.45 * hash01(plank, place, 11);
      const double grain = 0.9 + 0.1 * std::sin(x * 40.0 + 7.0 * hash01(plank, place, 12));
      const double gap = y / 0.15 - std::floor(y / 0.15) < 0.06 ? 0.5 : 1.0;
      return c * shade * grain * gap;
    }
    case FloorPattern::kConcrete:
      return c * (0.85 + 0.2 * valueNoise(x * 8, y * 8, place) +
                  0.05 * valueNoise(x * 40, y * 40, place + 3));
    case FloorPattern::kAsphalt: {
      // White bays every 2.5 m along x in the far half of the lot.
      const double bx = x / 2.5 - std::floor(x / 2.5);
      if (bx < 0.04 && y < -3.0 && y > -7.8) return {0.8, 0.8, 0.78};
      return c * (0.8 + 0.4 * valueNoise(x * 30, y * 30, place));
    }
    case FloorPattern::kGrass: {
      // A gravel path diagonally across.
      if (std::abs((x - 18.0) - (y - 0.0) * 0.9 - 1.0) < 0.5) return {0.45, 0.42, 0.36};
      return c * (0.7 + 0.5 * valueNoise(x * 12, y * 12, place) +
                  0.2 * valueNoise(x * 1.5, y * 1.5, place + 9));
    }
  }
  return c;
}

Eigen::Vector3d IndoorRenderer::wallAlbedo(int wall, int side, double s, double z) const {
  const IndoorWall& w = world_.walls[wall];
  const bool outdoor_side = side < 0 || world_.places[side].outdoor;
  if (outdoor_side) {
    if (w.height_m < 1.2) {  // fence: posts and rails
      const double ps = s / 2.0 - std::floor(s / 2.0);
      if (ps < 0.04 || std::abs(z - 1.0) < 0.04 || std::abs(z - 0.5) < 0.03)
        return {0.45, 0.47, 0.50};
      return world_.ground_rgb * (0.7 + 0.5 * valueNoise(s * 6, z * 6, wall));  // shrubs behind
    }
    if (w.height_m < 2.0)  // hedge
      return Eigen::Vector3d(0.12, 0.26, 0.08) *
             (0.6 + 0.7 * valueNoise(s * 8, z * 8, wall) + 0.2 * valueNoise(s * 30, z * 30, wall));
    // Brick facade: 0.075 m courses, 0.24 m bricks, staggered.
    const Eigen::Vector3d brick =
        side >= 0 ? world_.places[side].style.wall_rgb : Eigen::Vector3d(0.55, 0.30, 0.22);
    const auto course = static_cast<std::int64_t>(std::floor(z / 0.075));
    const double off = (course % 2) * 0.12;
    const double bs = (s + off) / 0.24;
    if (z / 0.075 - course < 0.12 || bs - std::floor(bs) < 0.05) return {0.62, 0.60, 0.55};
    return brick * (0.8 + 0.35 * hash01(course, static_cast<std::int64_t>(std::floor(bs)), wall));
  }
  const PlaceStyle& st = world_.places[side].style;
  Eigen::Vector3d base = st.wall_rgb * (0.95 + 0.06 * valueNoise(s * 2, z * 2, wall));
  if (z < 0.1) return base * 0.35;  // skirting
  const auto cell = static_cast<std::int64_t>(std::floor(s));
  const double x = s - std::floor(s);
  const double pick = hash01(wall, side, cell);
  double acc = 0.0;
  auto chosen = [&](double p) {
    const bool yes = pick >= acc && pick < acc + p;
    acc += p;
    return yes;
  };
  if (chosen(st.poster)) {
    if (x > 0.2 && x < 0.8 && z > 1.15 && z < 1.95) {
      if (x < 0.23 || x > 0.77 || z < 1.18 || z > 1.92) return {0.08, 0.08, 0.08};  // frame
      const Eigen::Vector3d a = randomColour(wall, cell, 1), b = randomColour(wall, cell, 5);
      const double split = 1.3 + 0.5 * hash01(wall, cell, 9);
      if (std::hypot(x - 0.5, z - 1.6) < 0.12 * (0.5 + hash01(wall, cell, 10)))
        return randomColour(wall, cell, 13);
      return z < split ? a : b;
    }
    return base;
  }
  if (chosen(st.shelf)) {
    if (x < 0.03 || x > 0.97 || z > 2.0) return z > 2.0 ? base : Eigen::Vector3d(0.30, 0.19, 0.09);
    const double row = z / 0.4;
    const auto r = static_cast<std::int64_t>(std::floor(row));
    if (row - r < 0.08) return {0.30, 0.19, 0.09};  // shelf board
    const auto spine = static_cast<std::int64_t>(std::floor(x / 0.035));
    const double top = 0.55 + 0.4 * hash01(wall, cell * 100 + spine, r);
    if (row - r > top) return {0.06, 0.05, 0.04};  // dark back above the books
    return randomColour(wall * 7 + r, cell, spine) * 0.8;
  }
  if (chosen(st.cabinet)) {
    const Eigen::Vector3d panel = hash01(wall, side, 77) < 0.5 ? Eigen::Vector3d(0.85, 0.85, 0.82)
                                                               : Eigen::Vector3d(0.55, 0.12, 0.10);
    if (z < 0.88)
      return std::abs(x - 0.5) < 0.01 || (z > 0.7 && z < 0.72 && x > 0.4 && x < 0.6)
                 ? Eigen::Vector3d(0.15, 0.15, 0.15)
                 : panel;
    if (z < 0.93) return {0.2, 0.2, 0.22};  // worktop edge
    if (z < 1.5) {                          // tiled splashback
      const double tx = x * 8 - std::floor(x * 8), tz = z * 8 - std::floor(z * 8);
      return tx < 0.06 || tz < 0.06 ? Eigen::Vector3d(0.5, 0.5, 0.5)
                                    : Eigen::Vector3d(0.35, 0.55, 0.60);
    }
    if (z < 2.2) return std::abs(x - 0.5) < 0.01 ? Eigen::Vector3d(0.15, 0.15, 0.15) : panel;
    return base;
  }
  if (chosen(st.board)) {
    if (x > 0.05 && x < 0.95 && z > 0.9 && z < 2.0) {
      if (x < 0.07 || x > 0.93 || z < 0.92 || z > 1.98) return {0.6, 0.6, 0.62};  // frame
      for (int k = 0; k < 3; ++k) {
        const double zc = 1.15 + 0.3 * k + 0.06 * std::sin(x * 25.0 + 6.0 * hash01(wall, cell, k));
        if (std::abs(z - zc) < 0.012 && hash01(wall, cell, k + 20) < 0.8)
          return randomColour(wall, cell, 30 + k) * 0.6;
      }
      return {0.93, 0.93, 0.92};
    }
    return base;
  }
  if (chosen(st.machine)) {
    if (x > 0.1 && x < 0.9 && z < 1.3) {
      if (z > 1.1 && z < 1.25 && x > 0.5 && x < 0.8) return {0.05, 0.35, 0.45};  // display
      if (z > 0.55 && z < 0.62) return {0.95, 0.95, 0.93};                       // paper tray
      return {0.62, 0.63, 0.65};
    }
    return base;
  }
  return base;
}

}  // namespace adaptive_perception::sim
