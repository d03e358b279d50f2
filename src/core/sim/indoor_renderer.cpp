#include "adaptive_perception/sim/indoor_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/world/lighting.h"
#include "procedural_texture.h"

namespace adaptive_perception::sim {

using texture::valueNoise;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDeg = M_PI / 180.0;

// Ray (origin o, direction d) against segment a-b in the plane: ray parameter t (in units of d,
// using d's xy part) and the segment parameter u in [0, 1]. False when parallel or missed.
bool raySegment(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector2d& a,
                const Eigen::Vector2d& b, double* t, double* u) {
  const Eigen::Vector2d e = b - a;
  const double den = d.x() * e.y() - d.y() * e.x();
  if (std::abs(den) < 1e-12) return false;
  const Eigen::Vector2d w(a.x() - o.x(), a.y() - o.y());
  *t = (w.x() * e.y() - w.y() * e.x()) / den;
  *u = (w.x() * d.y() - w.y() * d.x()) / den;
  return *t > 1e-9 && *u >= 0.0 && *u <= 1.0;
}

// Slab test of a ray against an axis-aligned box standing on the floor; entry t and the normal.
bool rayBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const IndoorBox& b, double* t,
            Eigen::Vector3d* n) {
  const Eigen::Vector3d lo(b.min_m.x(), b.min_m.y(), 0.0), hi(b.max_m.x(), b.max_m.y(), b.height_m);
  double t0 = 1e-9, t1 = kInf;
  int axis = -1;
  double sign = 0.0;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - o[k]) / d[k], tb = (hi[k] - o[k]) / d[k];
    double s = -1.0;
    if (ta > tb) {
      std::swap(ta, tb);
      s = 1.0;
    }
    if (ta > t0) {
      t0 = ta;
      axis = k;
      sign = s;
    }
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  if (axis < 0) return false;  // starts inside
  *t = t0;
  *n = Eigen::Vector3d::Zero();
  (*n)[axis] = sign;
  return true;
}

}  // namespace

const config::EnumNames<IndoorLightingKind>& indoorLightings() {
  static const config::EnumNames<IndoorLightingKind> names("lighting",
                                                           {{IndoorLightingKind::kNight, "night"},
                                                            {IndoorLightingKind::kCloudy, "cloudy"},
                                                            {IndoorLightingKind::kSunny, "sunny"}});
  return names;
}

IndoorLightingKind parseIndoorLighting(const std::string& name) {
  return indoorLightings().parse(name);
}
std::string indoorLightingName(IndoorLightingKind kind) { return indoorLightings().name(kind); }

IndoorLighting IndoorLighting::sample(IndoorLightingKind kind, math::Rng& rng) {
  IndoorLighting l;
  l.kind = kind;
  l.lamp_temperature_shift_k = rng.uniform(-300.0, 300.0);
  switch (kind) {
    case IndoorLightingKind::kNight:
      l.lamp_scale = rng.uniform(0.8, 1.2);
      l.daylight = 0.0;
      l.street_light = rng.uniform(0.15, 0.3);
      break;
    case IndoorLightingKind::kCloudy:
      l.lamp_scale = rng.uniform(0.45, 0.75);
      l.daylight = rng.uniform(0.8, 1.4);
      l.sky_temperature_k = rng.uniform(6500.0, 7500.0);
      break;
    case IndoorLightingKind::kSunny: {
      l.lamp_scale = rng.uniform(0.35, 0.6);
      l.daylight = rng.uniform(1.0, 1.5);
      l.sky_temperature_k = rng.uniform(8500.0, 11000.0);
      l.sun = rng.uniform(5.0, 8.0);
      l.sun_temperature_k = rng.uniform(4300.0, 5200.0);
      const double az = rng.uniform(0.0, 2.0 * M_PI), el = rng.uniform(25.0, 45.0) * kDeg;
      l.sun_direction = {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
      break;
    }
  }
  return l;
}

void IndoorCameraConfig::validate() const {
  auto need = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("indoor camera: " + what);
  };
  need(width_px >= 8 && height_px >= 8 && width_px <= 4096 && height_px <= 4096,
       "width_px and height_px must be in 8..4096");
  need(hfov_deg > 1.0 && hfov_deg < 170.0, "hfov_deg must be in (1, 170)");
  need(omni_width_px >= 8 && omni_height_px >= 8, "omni image size must be at least 8");
  need(inner_radius_px >= 0.0 && outer_radius_px > inner_radius_px,
       "omni radii need 0 <= inner_radius_px < outer_radius_px");
  need(max_elevation_deg > min_elevation_deg && min_elevation_deg > -90.0 &&
           max_elevation_deg < 90.0,
       "omni elevations need -90 < min_elevation_deg < max_elevation_deg < 90");
  need(height_m > 0.05, "height_m must exceed 0.05");
  need(exposure_target > 0.0 && exposure_target < 1.0, "exposure_target must be in (0, 1)");
  need(exposure_jitter >= 0.0, "exposure_jitter must be >= 0");
  sensor.validate();
}

struct IndoorRenderer::Hit {
  enum Kind { kNone, kWall, kFloor, kCeiling, kBox } kind = kNone;
  double t = kInf;
  int index = -1;  // wall or box
  double u = 0.0;  // along the wall, 0..1
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

IndoorRenderer::IndoorRenderer(IndoorWorld world, IndoorCameraConfig camera)
    : world_(std::move(world)), camera_(camera) {
  camera_.validate();
  const int w = camera_.width(), h = camera_.height();
  rays_body_.resize(static_cast<size_t>(w) * h);
  vignette_.resize(rays_body_.size());
  valid_.assign(rays_body_.size(), 1);
  if (!camera_.omni) {
    const double f = 0.5 * w / std::tan(0.5 * camera_.hfov_deg * kDeg);
    const double cp = std::cos(camera_.pitch_down_deg * kDeg),
                 sp = std::sin(camera_.pitch_down_deg * kDeg);
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        const double y = -(u + 0.5 - 0.5 * w) / f, z = -(v + 0.5 - 0.5 * h) / f;
        // Pitch down about the y axis: forward tips towards -z.
        rays_body_[v * w + u] = Eigen::Vector3d(cp - sp * z, y, sp + cp * z).normalized();
        const double r2 = (std::pow(u + 0.5 - 0.5 * w, 2) + std::pow(v + 0.5 - 0.5 * h, 2)) /
                          (0.25 * (w * w + h * h));
        vignette_[v * w + u] = static_cast<float>(camera_.sensor.falloff(r2));
      }
  } else {
    const double cx = 0.5 * w, cy = 0.5 * h;
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        const double dx = u + 0.5 - cx, dy = v + 0.5 - cy, r = std::hypot(dx, dy);
        const size_t i = static_cast<size_t>(v) * w + u;
        if (r > camera_.outer_radius_px) {
          valid_[i] = 0;
          continue;
        }
        if (r < camera_.inner_radius_px) {
          valid_[i] = 2;
          continue;
        }
        const double az = std::atan2(-dx, -dy);
        const double el =
            (camera_.min_elevation_deg +
             (r - camera_.inner_radius_px) / (camera_.outer_radius_px - camera_.inner_radius_px) *
                 (camera_.max_elevation_deg - camera_.min_elevation_deg)) *
            kDeg;
        rays_body_[i] = {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
        const double rr = r / camera_.outer_radius_px;
        vignette_[i] = static_cast<float>(camera_.sensor.falloff(rr * rr));
      }
  }
  // Daylight reaching each indoor place: window length on its boundary, saturating at 4 m.
  window_light_.assign(world_.places.size(), 0.0);
  for (size_t p = 0; p < world_.places.size(); ++p) {
    const IndoorPlace& pl = world_.places[p];
    if (pl.outdoor) continue;
    double len = 0.0;
    for (const IndoorWindow& win : world_.windows) {
      const Eigen::Vector2d mid = 0.5 * (win.a_m + win.b_m);
      const Eigen::Vector2d lo = pl.min_m.array() - 0.05, hi = pl.max_m.array() + 0.05;
      if ((mid.array() >= lo.array()).all() && (mid.array() <= hi.array()).all())
        len += (win.b_m - win.a_m).norm() * (win.top_m - win.bottom_m) / 1.3;
    }
    window_light_[p] = 0.08 + 0.35 * std::min(1.0, len / 4.0);
  }
}

bool IndoorRenderer::castRay(const Eigen::Vector3d& o, const Eigen::Vector3d& d, Hit* hit) const {
  Hit best;
  for (size_t i = 0; i < world_.walls.size(); ++i) {
    double t, u;
    if (!raySegment(o, d, world_.walls[i].a_m, world_.walls[i].b_m, &t, &u) || t >= best.t)
      continue;
    const double z = o.z() + t * d.z();
    if (z < 0.0 || z > world_.walls[i].height_m) continue;  // over the wall (or under the floor)
    best.kind = Hit::kWall;
    best.t = t;
    best.index = static_cast<int>(i);
    best.u = u;
  }
  for (size_t i = 0; i < world_.boxes.size(); ++i) {
    double t;
    Eigen::Vector3d n;
    if (rayBox(o, d, world_.boxes[i], &t, &n) && t < best.t) {
      best.kind = Hit::kBox;
      best.t = t;
      best.index = static_cast<int>(i);
      best.normal = n;
    }
  }
  if (d.z() < -1e-9) {
    const double t = -o.z() / d.z();
    if (t < best.t) {
      best.kind = Hit::kFloor;
      best.t = t;
      best.normal = {0, 0, 1};
    }
  } else if (d.z() > 1e-9) {
    const double t = (world_.ceiling_m - o.z()) / d.z();
    if (t > 0.0 && t < best.t) {
      const Eigen::Vector3d p = o + t * d;
      const int place = world_.placeAt(p.head<2>());
      if (place >= 0 && !world_.places[place].outdoor) {
        best.kind = Hit::kCeiling;
        best.t = t;
        best.normal = {0, 0, -1};
      }
    }
  }
  *hit = best;
  return best.kind != Hit::kNone;
}

bool IndoorRenderer::sunVisible(const Eigen::Vector3d& p, const IndoorLighting& l) const {
  const Eigen::Vector3d& d = l.sun_direction;
  if (d.z() <= 0.0) return false;
  for (const IndoorBox& b : world_.boxes) {
    double t;
    Eigen::Vector3d n;
    if (rayBox(p, d, b, &t, &n)) return false;
  }
  // Wall crossings in order: a crossing below the wall top blocks unless it is in a window; the
  // ceiling blocks when the ray climbs above it while over an indoor place.
  struct Crossing {
    double t;
    size_t wall;
  };
  std::vector<Crossing> crossings;
  for (size_t i = 0; i < world_.walls.size(); ++i) {
    double t, u;
    if (raySegment(p, d, world_.walls[i].a_m, world_.walls[i].b_m, &t, &u))
      crossings.push_back({t, i});
  }
  std::sort(crossings.begin(), crossings.end(),
            [](const Crossing& a, const Crossing& b) { return a.t < b.t; });
  int place = world_.placeAt(p.head<2>());
  for (const Crossing& c : crossings) {
    const Eigen::Vector3d q = p + c.t * d;
    if (place >= 0 && !world_.places[place].outdoor && q.z() > world_.ceiling_m) return false;
    const IndoorWall& w = world_.walls[c.wall];
    if (q.z() <= w.height_m) {
      bool through = false;
      for (const IndoorWindow& win : world_.windows) {
        const Eigen::Vector2d e = win.b_m - win.a_m;
        const double s = (q.head<2>() - win.a_m).dot(e) / e.squaredNorm();
        const double off = (win.a_m + s * e - q.head<2>()).norm();
        if (s >= 0.0 && s <= 1.0 && off < 0.02 && q.z() >= win.bottom_m && q.z() <= win.top_m) {
          through = true;
          break;
        }
      }
      if (!through) return false;
    }
    place = world_.placeAt((q + 0.02 * d).head<2>());
  }
  if (place >= 0 && !world_.places[place].outdoor) return false;  // under the ceiling
  return true;
}

IndoorRenderer::Sources IndoorRenderer::sources(const IndoorLighting& l) const {
  using world::colorTemperatureRgb;
  const double wp = camera_.sensor.white_point_k;
  Sources src{l, colorTemperatureRgb(l.sky_temperature_k, wp),
              colorTemperatureRgb(l.sun_temperature_k, wp), colorTemperatureRgb(2100.0, wp), {}};
  for (const auto& place : world_.places)
    src.lamp.push_back(
        colorTemperatureRgb(place.style.lamp_color_temperature_k + l.lamp_temperature_shift_k, wp));
  return src;
}

Eigen::Vector3d IndoorRenderer::skyRadiance(const Eigen::Vector3d& d, const Sources& src) const {
  const IndoorLighting& l = src.lighting;
  if (l.kind == IndoorLightingKind::kNight) return {0.004, 0.005, 0.012};
  const Eigen::Vector3d& sky = src.sky;
  if (d.z() < 0.0) {  // below the horizon: distant trees and lawns
    return l.daylight * 0.25 * Eigen::Vector3d(0.18, 0.28, 0.12).cwiseProduct(sky) *
           (1.0 + (l.kind == IndoorLightingKind::kSunny ? 1.5 : 0.0));
  }
  if (l.kind == IndoorLightingKind::kCloudy)
    return l.daylight * 1.4 * Eigen::Vector3d(0.80, 0.82, 0.86).cwiseProduct(sky);
  // Clear sky: deeper blue overhead.
  const double up = std::clamp(d.z(), 0.0, 1.0);
  const Eigen::Vector3d horizon(0.70, 0.80, 0.95), zenith(0.25, 0.45, 0.95);
  return l.daylight * 1.6 * ((1.0 - up) * horizon + up * zenith).cwiseProduct(sky);
}

Eigen::Vector3d IndoorRenderer::irradiance(const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                                           int place, double lamp_factor,
                                           const Sources& src) const {
  const IndoorLighting& l = src.lighting;
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  const bool outdoor = place < 0 || world_.places[place].outdoor;
  if (!outdoor) {
    const PlaceStyle& s = world_.places[place].style;
    e += lamp_factor * s.lamp_intensity * l.lamp_scale * src.lamp[place];
    e += l.daylight * window_light_[place] * src.sky;
  } else {
    e += l.street_light * src.street;
    e += l.daylight * 1.8 * (0.6 + 0.4 * std::max(0.0, n.z())) * src.sky;
  }
  if (l.sun > 0.0) {
    const double cos_in = n.dot(l.sun_direction);
    if (cos_in > 0.0 && sunVisible(p + 0.01 * n, l)) e += l.sun * cos_in * src.sun;
  }
  return e;
}

Eigen::Vector3d IndoorRenderer::radiance(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                         const IndoorLighting& l) const {
  return radiance(o, d, sources(l));
}

Eigen::Vector3d IndoorRenderer::radiance(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                         const Sources& src) const {
  const IndoorLighting& l = src.lighting;
  Hit hit;
  if (!castRay(o, d, &hit)) return skyRadiance(d, src);
  const Eigen::Vector3d p = o + hit.t * d;
  switch (hit.kind) {
    case Hit::kFloor: {
      const int place = world_.placeAt(p.head<2>());
      return floorAlbedo(place, p.x(), p.y())
          .cwiseProduct(irradiance(p, hit.normal, place, 1.0, src));
    }
    case Hit::kCeiling: {
      const int place = world_.placeAt(p.head<2>());
      const double gx = p.x() / 2.0 - std::floor(p.x() / 2.0),
                   gy = p.y() / 2.0 - std::floor(p.y() / 2.0);
      if (std::abs(gx - 0.5) < 0.15 && std::abs(gy - 0.5) < 0.3) {  // lamp panel: emits
        const PlaceStyle& s = world_.places[place].style;
        return 1.6 * s.lamp_intensity * l.lamp_scale * src.lamp[place];
      }
      return Eigen::Vector3d(0.85, 0.85, 0.83)
          .cwiseProduct(irradiance(p, hit.normal, place, 0.45, src));
    }
    case Hit::kBox: {
      const IndoorBox& b = world_.boxes[hit.index];
      const int place = world_.placeAt(p.head<2>());
      const double shade = hit.normal.z() > 0.5 ? 1.0 : 0.8;
      const Eigen::Vector3d tex =
          b.rgb * shade * (0.92 + 0.12 * valueNoise(p.x() * 10 + p.z() * 7, p.y() * 10, hit.index));
      return tex.cwiseProduct(irradiance(p, hit.normal, place, 0.9, src));
    }
    case Hit::kWall: {
      const IndoorWall& w = world_.walls[hit.index];
      const Eigen::Vector2d e = (w.b_m - w.a_m).normalized();
      Eigen::Vector3d n(-e.y(), e.x(), 0.0);
      if (n.dot(d) > 0.0) n = -n;
      const Eigen::Vector2d dxy = d.head<2>().normalized();
      const int side = world_.placeAt(p.head<2>() - 0.02 * dxy);
      const bool indoor_side = side >= 0 && !world_.places[side].outdoor;
      for (const IndoorWindow& win : world_.windows) {
        const Eigen::Vector2d we = win.b_m - win.a_m;
        const double s = (p.head<2>() - win.a_m).dot(we) / we.squaredNorm();
        const double off = (win.a_m + s * we - p.head<2>()).norm();
        if (s < 0.0 || s > 1.0 || off > 0.02 || p.z() < win.bottom_m || p.z() > win.top_m) continue;
        const double along = s * we.norm();
        const bool frame = along < 0.05 || (we.norm() - along) < 0.05 ||
                           p.z() - win.bottom_m < 0.05 || win.top_m - p.z() < 0.05 ||
                           std::abs(along - std::round(along / 1.2) * 1.2) < 0.03;
        if (frame)
          return Eigen::Vector3d(0.8, 0.8, 0.8).cwiseProduct(irradiance(p, n, side, 0.8, src));
        if (indoor_side) return skyRadiance(d, src);  // the view outside
        // Glass seen from outside: dark, with a reflection of the sky.
        Eigen::Vector3d r = d;
        r.head<2>() -= 2.0 * r.head<2>().dot(n.head<2>()) * n.head<2>();
        return 0.25 * skyRadiance(r, src) + Eigen::Vector3d(0.01, 0.012, 0.015);
      }
      const double s_m = hit.u * (w.b_m - w.a_m).norm();
      return wallAlbedo(hit.index, side, s_m, p.z()).cwiseProduct(irradiance(p, n, side, 0.8, src));
    }
    case Hit::kNone:
      break;
  }
  return skyRadiance(d, src);
}

cv::Mat IndoorRenderer::render(const math::SE2& pose, const IndoorLighting& l,
                               math::Rng& rng) const {
  const int w = camera_.width(), h = camera_.height();
  const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
  const Eigen::Vector3d origin(pose.x_m, pose.y_m, camera_.height_m);
  const Sources src = sources(l);
  std::vector<Eigen::Vector3f> lin(rays_body_.size(), Eigen::Vector3f::Zero());
  double lum_sum = 0.0;
  long lum_n = 0;
  for (size_t i = 0; i < rays_body_.size(); ++i) {
    if (valid_[i] != 1) continue;
    const Eigen::Vector3d& b = rays_body_[i];
    const Eigen::Vector3d d(c * b.x() - s * b.y(), s * b.x() + c * b.y(), b.z());
    const Eigen::Vector3d r = radiance(origin, d, src) * vignette_[i];
    lin[i] = r.cast<float>();
    lum_sum += 0.299 * r.x() + 0.587 * r.y() + 0.114 * r.z();
    ++lum_n;
  }
  // Auto-exposure: bring the mean luminance to the target (the paper's auto-brightness).
  const double mean = lum_n > 0 ? lum_sum / lum_n : 1.0;
  const double gain = camera_.exposure_target / std::max(mean, 1e-6) *
                      std::max(0.2, 1.0 + rng.gaussian(0.0, camera_.exposure_jitter));
  cv::Mat out(h, w, CV_8UC3);
  for (int v = 0; v < h; ++v) {
    cv::Vec3b* row = out.ptr<cv::Vec3b>(v);
    for (int u = 0; u < w; ++u) {
      const size_t i = static_cast<size_t>(v) * w + u;
      if (valid_[i] == 0) {
        row[u] = {0, 0, 0};
        continue;
      }
      Eigen::Vector3d px = valid_[i] == 2 ? Eigen::Vector3d(0.0006, 0.0006, 0.0007)
                                          : (lin[i].cast<double>() * gain).eval();
      for (int k = 0; k < 3; ++k) {
        double level = camera_.sensor.level(px[k]);
        level = std::clamp(level + rng.gaussian(0.0, camera_.sensor.noiseSd(level)), 0.0, 255.0);
        row[u][2 - k] = static_cast<unsigned char>(std::lround(level));
      }
    }
  }
  return out;
}

}  // namespace adaptive_perception::sim
