#include "adaptive_perception/world/field_map.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>

namespace adaptive_perception::world {

void FieldDimensions::validate() const {
  auto positive = [](const char* name, double v) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw std::invalid_argument(std::string(name) + " = " + std::to_string(v) +
                                  " must be a positive finite number");
  };
  positive("field_length_m", field_length_m);
  positive("field_width_m", field_width_m);
  positive("carpet_margin_m", carpet_margin_m);
  positive("line_width_m", line_width_m);
  positive("centre_circle_diameter_m", centre_circle_diameter_m);
  positive("penalty_area_depth_m", penalty_area_depth_m);
  positive("penalty_area_width_m", penalty_area_width_m);
  positive("wall_height_m", wall_height_m);
  positive("goal_width_m", goal_width_m);
  positive("goal_depth_m", goal_depth_m);
  positive("goal_height_m", goal_height_m);
  positive("beacon_radius_m", beacon_radius_m);
  positive("beacon_white_height_m", beacon_white_height_m);
  positive("beacon_band_height_m", beacon_band_height_m);
  positive("ball_radius_m", ball_radius_m);
  auto check = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  check(goal_width_m < field_width_m, "goal_width_m must be less than field_width_m");
  check(goal_depth_m <= carpet_margin_m,
        "goal_depth_m must fit in carpet_margin_m (the goal stands behind the goal line)");
  check(penalty_area_width_m < field_width_m && penalty_area_depth_m < 0.5 * field_length_m,
        "the penalty area must fit in its half of the field");
  check(centre_circle_diameter_m < field_width_m,
        "centre_circle_diameter_m must be less than field_width_m");
  check(std::fabs(beacon_x_m) < 0.5 * field_length_m + carpet_margin_m &&
            std::fabs(beacon_y_m) + beacon_radius_m < 0.5 * field_width_m + carpet_margin_m,
        "the beacons (beacon_x_m, beacon_y_m) must stand on the carpet inside the field wall");
  check(3.0 * line_width_m < centre_circle_diameter_m,
        "line_width_m is too wide for the centre circle");
}

FieldMap::FieldMap(const FieldDimensions& d) : dims_(d) {
  d.validate();
  const double hl = 0.5 * d.field_length_m, hw = 0.5 * d.field_width_m, lw = d.line_width_m;
  carpet_half_length_m_ = hl + d.carpet_margin_m;
  carpet_half_width_m_ = hw + d.carpet_margin_m;
  const double cl = carpet_half_length_m_, cw = carpet_half_width_m_;

  // Lines: outer edges of the border lines lie on the field boundary.
  rects_.push_back({-hl, hw - lw, hl, hw, kWhite});          // left side line
  rects_.push_back({-hl, -hw, hl, -hw + lw, kWhite});        // right side line
  rects_.push_back({-hl, -hw, -hl + lw, hw, kWhite});        // yellow goal line
  rects_.push_back({hl - lw, -hw, hl, hw, kWhite});          // cyan goal line
  rects_.push_back({-0.5 * lw, -hw, 0.5 * lw, hw, kWhite});  // halfway line
  for (double sign : {-1.0, 1.0}) {                          // penalty areas
    const double front = sign * (hl - d.penalty_area_depth_m);
    const double ph = 0.5 * d.penalty_area_width_m;
    const double xa = std::min(front, sign * hl), xb = std::max(front, sign * hl);
    rects_.push_back({front - 0.5 * lw, -ph, front + 0.5 * lw, ph, kWhite});
    rects_.push_back({xa, ph - lw, xb, ph, kWhite});
    rects_.push_back({xa, -ph, xb, -ph + lw, kWhite});
  }
  const double r = 0.5 * d.centre_circle_diameter_m;
  rings_.push_back({0.0, 0.0, r - 0.5 * lw, r + 0.5 * lw, kWhite});

  // Field wall around the carpet.
  const double wh = d.wall_height_m;
  quads_.push_back({{-cl, -cw}, {cl, -cw}, 0.0, wh, kWhite, SurfaceKind::kWall});
  quads_.push_back({{cl, -cw}, {cl, cw}, 0.0, wh, kWhite, SurfaceKind::kWall});
  quads_.push_back({{cl, cw}, {-cl, cw}, 0.0, wh, kWhite, SurfaceKind::kWall});
  quads_.push_back({{-cl, cw}, {-cl, -cw}, 0.0, wh, kWhite, SurfaceKind::kWall});

  // Goals: back panel and two side panels behind each goal line; yellow at -x, cyan at +x.
  const double gh = 0.5 * d.goal_width_m;
  for (double sign : {-1.0, 1.0}) {
    const ColorClass c = sign < 0 ? kYellow : kCyan;
    const double x_line = sign * hl, x_back = sign * (hl + d.goal_depth_m);
    quads_.push_back({{x_back, -gh}, {x_back, gh}, 0.0, d.goal_height_m, c, SurfaceKind::kGoal});
    quads_.push_back({{x_line, gh}, {x_back, gh}, 0.0, d.goal_height_m, c, SurfaceKind::kGoal});
    quads_.push_back({{x_line, -gh}, {x_back, -gh}, 0.0, d.goal_height_m, c, SurfaceKind::kGoal});
  }

  // Beacons. Looking from the yellow goal (-x) to the cyan goal (+x): on the right (-y) the top
  // band is pink and the lower band has the colour of the nearer goal; on the left (+y) it is the
  // other way round.
  const double zw = d.beacon_white_height_m, zb = zw + d.beacon_band_height_m,
               za = zb + d.beacon_band_height_m;
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      const ColorClass goal = sx < 0 ? kYellow : kCyan;
      const ColorClass lower = sy < 0 ? goal : kPink;
      const ColorClass upper = sy < 0 ? kPink : goal;
      Cylinder cyl{sx * d.beacon_x_m,
                   sy * d.beacon_y_m,
                   d.beacon_radius_m,
                   {{0.0, zw, kWhite}, {zw, zb, lower}, {zb, za, upper}},
                   colorClassName(upper) + "_over_" + colorClassName(lower)};
      cylinders_.push_back(cyl);
    }
  }
  if (d.ball_enabled) {
    spheres_.push_back({Eigen::Vector3d(d.ball_xy_m.x(), d.ball_xy_m.y(), d.ball_radius_m),
                        d.ball_radius_m, kOrange});
  }
}

ColorClass FieldMap::groundColorAt(double x, double y) const {
  if (std::fabs(x) > carpet_half_length_m_ || std::fabs(y) > carpet_half_width_m_)
    return kBackground;
  for (const auto& g : rects_)
    if (x >= g.x0_m && x <= g.x1_m && y >= g.y0_m && y <= g.y1_m) return g.color;
  for (const auto& g : rings_) {
    const double r2 = (x - g.cx_m) * (x - g.cx_m) + (y - g.cy_m) * (y - g.cy_m);
    if (r2 >= g.r_inner_m * g.r_inner_m && r2 <= g.r_outer_m * g.r_outer_m) return g.color;
  }
  return kGreen;
}

bool FieldMap::isFree(double x, double y, double margin) const {
  if (std::fabs(x) > carpet_half_length_m_ - margin || std::fabs(y) > carpet_half_width_m_ - margin)
    return false;
  const double hl = 0.5 * dims_.field_length_m;
  if (std::fabs(x) > hl - margin && std::fabs(y) < 0.5 * dims_.goal_width_m + margin) return false;
  for (const auto& c : cylinders_) {
    const double rr = c.radius_m + margin;
    if ((x - c.cx_m) * (x - c.cx_m) + (y - c.cy_m) * (y - c.cy_m) < rr * rr) return false;
  }
  return true;
}

FieldDimensions FieldMap::parseYaml(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(source + ":" + std::to_string(e.mark.line + 1) +
                             ": YAML syntax error: " + e.msg);
  }
  FieldDimensions d;
  // Keys left out keep their defaults, but a file without any (empty, or only comments) is a mistake.
  if (!root || root.IsNull())
    throw std::runtime_error(source + ": no field dimensions in the file (empty?)");
  if (!root.IsMap()) throw std::runtime_error(source + ": expected a map of field dimensions");
  std::map<std::string, double*> numbers = {
      {"field_length_m", &d.field_length_m},
      {"field_width_m", &d.field_width_m},
      {"carpet_margin_m", &d.carpet_margin_m},
      {"line_width_m", &d.line_width_m},
      {"centre_circle_diameter_m", &d.centre_circle_diameter_m},
      {"penalty_area_depth_m", &d.penalty_area_depth_m},
      {"penalty_area_width_m", &d.penalty_area_width_m},
      {"wall_height_m", &d.wall_height_m},
      {"goal_width_m", &d.goal_width_m},
      {"goal_depth_m", &d.goal_depth_m},
      {"goal_height_m", &d.goal_height_m},
      {"beacon_x_m", &d.beacon_x_m},
      {"beacon_y_m", &d.beacon_y_m},
      {"beacon_radius_m", &d.beacon_radius_m},
      {"beacon_white_height_m", &d.beacon_white_height_m},
      {"beacon_band_height_m", &d.beacon_band_height_m},
      {"ball_radius_m", &d.ball_radius_m},
  };
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>();
    const int line = kv.first.Mark().line + 1;
    const std::string where = source + ":" + std::to_string(line) + ": ";
    try {
      if (auto it = numbers.find(key); it != numbers.end()) {
        *it->second = kv.second.as<double>();
      } else if (key == "ball_enabled") {
        d.ball_enabled = kv.second.as<bool>();
      } else if (key == "ball_xy_m") {
        const auto v = kv.second.as<std::vector<double>>();
        if (v.size() != 2) throw std::runtime_error(where + "ball_xy_m needs two numbers [x, y]");
        d.ball_xy_m = {v[0], v[1]};
      } else {
        throw std::runtime_error(where + "unknown key '" + key + "'");
      }
    } catch (const YAML::Exception& e) {
      throw std::runtime_error(where + "bad value for '" + key + "': " + e.msg);
    }
  }
  try {
    d.validate();
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(source + ": " + e.what());
  }
  return d;
}

FieldMap FieldMap::loadYaml(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open field map file");
  std::stringstream ss;
  ss << in.rdbuf();
  return FieldMap(parseYaml(ss.str(), path));
}

}  // namespace adaptive_perception::world
