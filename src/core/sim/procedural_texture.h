#pragma once
// Deterministic procedural textures for the indoor renderer (private to src/core/sim): hashing,
// value noise and random colours, so that the building looks the same in every run.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace adaptive_perception::sim::texture {

inline std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
inline double hash01(std::int64_t a, std::int64_t b = 0, std::int64_t c = 0) {
  const std::uint64_t h =
      mix(mix(mix(static_cast<std::uint64_t>(a)) ^ static_cast<std::uint64_t>(b)) ^
          static_cast<std::uint64_t>(c));
  return (h >> 11) * (1.0 / 9007199254740992.0);
}
// Bilinear value noise in [0, 1] on a unit lattice.
inline double valueNoise(double x, double y, int seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
  const double tx = x - fx, ty = y - fy;
  const double sx = tx * tx * (3 - 2 * tx), sy = ty * ty * (3 - 2 * ty);
  const double a = hash01(ix, iy, seed), b = hash01(ix + 1, iy, seed);
  const double c = hash01(ix, iy + 1, seed), d = hash01(ix + 1, iy + 1, seed);
  return (a * (1 - sx) + b * sx) * (1 - sy) + (c * (1 - sx) + d * sx) * sy;
}
// A saturated-ish random colour.
inline Eigen::Vector3d randomColour(std::int64_t a, std::int64_t b, std::int64_t c) {
  const double h = hash01(a, b, c) * 6.0, s = 0.45 + 0.5 * hash01(a, b, c + 1),
               v = 0.25 + 0.65 * hash01(a, b, c + 2);
  const int i = static_cast<int>(h) % 6;
  const double f = h - std::floor(h);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (i) {
    case 0:
      return {v, t, p};
    case 1:
      return {q, v, p};
    case 2:
      return {p, v, t};
    case 3:
      return {p, q, v};
    case 4:
      return {t, p, v};
    default:
      return {v, p, q};
  }
}

}  // namespace adaptive_perception::sim::texture
