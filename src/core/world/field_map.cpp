#include "adaptive_perception/world/field_map.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <stdexcept>

#include "adaptive_perception/io/yaml_file.h"

namespace adaptive_perception::world {

std::vector<Landmark> fourLeggedBeacons() {
  std::vector<Landmark> out;
  for (double sx : {-1.0, 1.0}) {
    for (double sy : {-1.0, 1.0}) {
      const ColorClass goal = sx < 0 ? kYellow : kCyan;
      const ColorClass lower = sy < 0 ? goal : kPink;
      const ColorClass upper = sy < 0 ? kPink : goal;
      out.push_back(
          {"", {sx * 1.35, sy * 1.95}, 0.05, {{kWhite, 0.2}, {lower, 0.1}, {upper, 0.1}}});
    }
  }
  return out;
}

void FieldDimensions::validate() const {
  auto positive = [](const std::string& name, double v) {
    if (!(v > 0.0) || !std::isfinite(v))
      throw std::invalid_argument(name + " = " + std::to_string(v) +
                                  " must be a positive finite number");
  };
  auto nonNegative = [](const char* name, double v) {
    if (!(v >= 0.0) || !std::isfinite(v))
      throw std::invalid_argument(std::string(name) + " = " + std::to_string(v) +
                                  " must be zero or a positive finite number");
  };
  positive("field_length_m", field_length_m);
  positive("field_width_m", field_width_m);
  positive("carpet_margin_m", carpet_margin_m);
  positive("line_width_m", line_width_m);
  positive("centre_circle_diameter_m", centre_circle_diameter_m);
  positive("penalty_area_depth_m", penalty_area_depth_m);
  positive("penalty_area_width_m", penalty_area_width_m);
  nonNegative("goal_area_depth_m", goal_area_depth_m);
  nonNegative("goal_area_width_m", goal_area_width_m);
  nonNegative("penalty_mark_distance_m", penalty_mark_distance_m);
  positive("mark_size_m", mark_size_m);
  nonNegative("wall_height_m", wall_height_m);
  positive("goal_width_m", goal_width_m);
  positive("goal_depth_m", goal_depth_m);
  positive("goal_height_m", goal_height_m);
  nonNegative("goal_post_diameter_m", goal_post_diameter_m);
  positive("ball_radius_m", ball_radius_m);
  auto check = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  const double hl = 0.5 * field_length_m, hw = 0.5 * field_width_m;
  check(goal_width_m + 2.0 * goal_post_diameter_m < field_width_m,
        "goal_width_m (with its posts) must be less than field_width_m");
  check(goal_depth_m <= carpet_margin_m,
        "goal_depth_m must fit in carpet_margin_m (the goal stands behind the goal line)");
  check(goal_post_diameter_m < goal_height_m,
        "goal_post_diameter_m must be less than goal_height_m");
  check(penalty_area_width_m < field_width_m && penalty_area_depth_m < hl,
        "the penalty area must fit in its half of the field");
  check((goal_area_depth_m == 0.0) == (goal_area_width_m == 0.0),
        "goal_area_depth_m and goal_area_width_m are both zero (no goal area) or both positive");
  check(goal_area_depth_m < penalty_area_depth_m && goal_area_width_m < penalty_area_width_m,
        "the goal area must fit in the penalty area");
  check(penalty_mark_distance_m == 0.0 ||
            (penalty_mark_distance_m + 0.5 * mark_size_m < hl &&
             penalty_mark_distance_m > 0.5 * mark_size_m + line_width_m),
        "penalty_mark_distance_m must put the mark inside its half, clear of the goal line");
  check(mark_size_m > line_width_m, "mark_size_m must be longer than line_width_m");
  check(centre_circle_diameter_m < field_width_m,
        "centre_circle_diameter_m must be less than field_width_m");
  check(3.0 * line_width_m < centre_circle_diameter_m,
        "line_width_m is too wide for the centre circle");
  for (ColorClass c : {goal_color_minus_x, goal_color_plus_x, ball_color})
    check(c < kNumColorClasses, "goal and ball colours must be colour classes");
  for (size_t i = 0; i < landmarks.size(); ++i) {
    const Landmark& l = landmarks[i];
    const std::string name = "landmarks[" + std::to_string(i) + "]";
    check(!l.bands.empty(), name + " has no bands");
    positive(name + ".radius_m", l.radius_m);
    for (const LandmarkBand& b : l.bands) {
      positive(name + " band height_m", b.height_m);
      check(b.color < kNumColorClasses, name + " has a band of no colour class");
    }
    check(std::isfinite(l.xy_m.x()) && std::isfinite(l.xy_m.y()) &&
              std::fabs(l.xy_m.x()) + l.radius_m <= hl + carpet_margin_m &&
              std::fabs(l.xy_m.y()) + l.radius_m <= hw + carpet_margin_m,
          name + " must stand on the carpet (x_m, y_m inside the carpet margin)");
  }
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
  rects_.push_back({-hl, -hw, -hl + lw, hw, kWhite});        // -x goal line
  rects_.push_back({hl - lw, -hw, hl, hw, kWhite});          // +x goal line
  rects_.push_back({-0.5 * lw, -hw, 0.5 * lw, hw, kWhite});  // halfway line
  auto box = [&](double sign, double depth, double width) {  // penalty or goal area
    const double front = sign * (hl - depth);
    const double ph = 0.5 * width;
    const double xa = std::min(front, sign * hl), xb = std::max(front, sign * hl);
    rects_.push_back({front - 0.5 * lw, -ph, front + 0.5 * lw, ph, kWhite});
    rects_.push_back({xa, ph - lw, xb, ph, kWhite});
    rects_.push_back({xa, -ph, xb, -ph + lw, kWhite});
  };
  auto cross = [&](double x, double y) {  // a mark: two bars of line width
    const double a = 0.5 * d.mark_size_m, w = 0.5 * lw;
    rects_.push_back({x - a, y - w, x + a, y + w, kWhite});
    rects_.push_back({x - w, y - a, x + w, y + a, kWhite});
  };
  for (double sign : {-1.0, 1.0}) box(sign, d.penalty_area_depth_m, d.penalty_area_width_m);
  if (d.goal_area_depth_m > 0.0)
    for (double sign : {-1.0, 1.0}) box(sign, d.goal_area_depth_m, d.goal_area_width_m);
  if (d.penalty_mark_distance_m > 0.0)
    for (double sign : {-1.0, 1.0}) cross(sign * (hl - d.penalty_mark_distance_m), 0.0);
  if (d.centre_mark) cross(0.0, 0.0);
  const double r = 0.5 * d.centre_circle_diameter_m;
  rings_.push_back({0.0, 0.0, r - 0.5 * lw, r + 0.5 * lw, kWhite});
  indexGround();

  // Field wall around the carpet.
  const double wh = d.wall_height_m;
  if (wh > 0.0) {
    quads_.push_back({{-cl, -cw}, {cl, -cw}, 0.0, wh, kWhite, SurfaceKind::kWall});
    quads_.push_back({{cl, -cw}, {cl, cw}, 0.0, wh, kWhite, SurfaceKind::kWall});
    quads_.push_back({{cl, cw}, {-cl, cw}, 0.0, wh, kWhite, SurfaceKind::kWall});
    quads_.push_back({{-cl, cw}, {-cl, -cw}, 0.0, wh, kWhite, SurfaceKind::kWall});
  }

  // Goals behind each goal line: panels (back and two sides) in the goal's colour, or two posts
  // and a crossbar in its colour with the net's panels behind.
  const double gh = 0.5 * d.goal_width_m, gt = d.goal_height_m;
  for (double sign : {-1.0, 1.0}) {
    const ColorClass c = sign < 0 ? d.goal_color_minus_x : d.goal_color_plus_x;
    const double x_line = sign * hl, x_back = sign * (hl + d.goal_depth_m);
    const bool posts = d.goal_post_diameter_m > 0.0;
    const ColorClass panel = posts ? d.goal_net_color : c;
    if (panel != kBackground) {
      quads_.push_back({{x_back, -gh}, {x_back, gh}, 0.0, gt, panel, SurfaceKind::kGoal});
      quads_.push_back({{x_line, gh}, {x_back, gh}, 0.0, gt, panel, SurfaceKind::kGoal});
      quads_.push_back({{x_line, -gh}, {x_back, -gh}, 0.0, gt, panel, SurfaceKind::kGoal});
    }
    if (posts) {
      const double pr = 0.5 * d.goal_post_diameter_m;
      const double x_post = sign * (hl - lw + pr);  // the posts' fronts on the line's front edge
      for (double side : {-1.0, 1.0}) {
        cylinders_.push_back({x_post,
                              side * (gh + pr),
                              pr,
                              {{0.0, gt, c}},
                              std::string(sign < 0 ? "minus_x" : "plus_x") + "_goal_post",
                              SurfaceKind::kGoal});
      }
      quads_.push_back({{x_post, -gh - pr},
                        {x_post, gh + pr},
                        gt - d.goal_post_diameter_m,
                        gt,
                        c,
                        SurfaceKind::kGoal});  // the crossbar, as a flat bar through the posts
    }
  }

  for (const Landmark& l : d.landmarks) {
    Cylinder cyl{l.xy_m.x(), l.xy_m.y(), l.radius_m, {}, l.name, SurfaceKind::kBeacon};
    double z = 0.0;
    for (const LandmarkBand& b : l.bands) {
      cyl.bands.push_back({z, z + b.height_m, b.color});
      z += b.height_m;
    }
    if (cyl.name.empty()) {
      cyl.name = colorClassName(l.bands.back().color);
      if (l.bands.size() > 1)
        cyl.name += "_over_" + colorClassName(l.bands[l.bands.size() - 2].color);
    }
    cylinders_.push_back(cyl);
  }
  if (d.ball_enabled) {
    spheres_.push_back({Eigen::Vector3d(d.ball_xy_m.x(), d.ball_xy_m.y(), d.ball_radius_m),
                        d.ball_radius_m, d.ball_color});
  }
}

void FieldMap::indexGround() {
  const double cl = carpet_half_length_m_, cw = carpet_half_width_m_;
  // 0.25 m cells, coarser on a carpet over 256 m a side (at most 1024 cells a side).
  ground_cell_m_ = std::max(0.25, 2.0 * std::max(cl, cw) / 1024.0);
  const double s = ground_cell_m_;
  ground_cols_ = std::clamp(static_cast<int>(std::ceil(2.0 * cl / s)), 1, 1024);
  ground_rows_ = std::clamp(static_cast<int>(std::ceil(2.0 * cw / s)), 1, 1024);
  // A cell's shapes are those whose bounding box meets the cell grown by a margin far above the
  // rounding of the lookup's cell arithmetic, so that a point is never looked up in a cell whose
  // list misses a shape containing it.
  const double margin = 1e-6;
  auto touches = [&](int cx, int cy, double x0, double y0, double x1, double y1) {
    const double a = -cl + cx * s, b = -cw + cy * s;
    return x0 <= a + s + margin && x1 >= a - margin && y0 <= b + s + margin && y1 >= b - margin;
  };
  ground_begin_.assign(static_cast<size_t>(ground_cols_) * ground_rows_ + 1, 0);
  ground_shapes_.clear();
  for (int cy = 0; cy < ground_rows_; ++cy)
    for (int cx = 0; cx < ground_cols_; ++cx) {
      for (size_t i = 0; i < rects_.size(); ++i) {
        const GroundRect& g = rects_[i];
        if (touches(cx, cy, g.x0_m, g.y0_m, g.x1_m, g.y1_m))
          ground_shapes_.push_back(static_cast<int>(i));
      }
      for (size_t i = 0; i < rings_.size(); ++i) {
        const GroundRing& g = rings_[i];
        if (touches(cx, cy, g.cx_m - g.r_outer_m, g.cy_m - g.r_outer_m, g.cx_m + g.r_outer_m,
                    g.cy_m + g.r_outer_m))
          ground_shapes_.push_back(static_cast<int>(rects_.size() + i));
      }
      ground_begin_[static_cast<size_t>(cy) * ground_cols_ + cx + 1] =
          static_cast<int>(ground_shapes_.size());
    }
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

namespace {

std::string at(const std::string& source, const YAML::Node& node) {
  return source + ":" + std::to_string(node.Mark().line + 1) + ": ";
}

ColorClass colorValue(const YAML::Node& node, const std::string& where, const std::string& key,
                      bool allow_none) {
  const std::string name = node.as<std::string>();
  if (allow_none && name == "none") return kBackground;
  const auto c = parseColorClass(name);
  if (!c) {
    std::string names;
    for (const char* n : colorClassNames()) names += std::string(names.empty() ? "" : ", ") + n;
    throw std::runtime_error(where + key + ": unknown colour '" + name + "' (one of " + names +
                             (allow_none ? ", none)" : ")"));
  }
  return *c;
}

Landmark landmarkValue(const YAML::Node& node, const std::string& source) {
  const std::string where = at(source, node);
  if (!node.IsMap())
    throw std::runtime_error(where + "a landmark is a map {name, x_m, y_m, radius_m, bands}");
  Landmark l;
  bool has_x = false, has_y = false, has_bands = false;
  for (const auto& kv : node) {
    const std::string key = kv.first.as<std::string>();
    const std::string w = at(source, kv.first);
    try {
      if (key == "name") {
        l.name = kv.second.as<std::string>();
      } else if (key == "x_m") {
        l.xy_m.x() = kv.second.as<double>();
        has_x = true;
      } else if (key == "y_m") {
        l.xy_m.y() = kv.second.as<double>();
        has_y = true;
      } else if (key == "radius_m") {
        l.radius_m = kv.second.as<double>();
      } else if (key == "bands") {
        if (!kv.second.IsSequence())
          throw std::runtime_error(w + "bands is a list [{color, height_m}, ...], bottom first");
        for (const auto& b : kv.second) {
          const std::string wb = at(source, b);
          if (!b.IsMap() || !b["color"] || !b["height_m"] || b.size() != 2)
            throw std::runtime_error(wb + "a band is {color: NAME, height_m: H} and nothing else");
          l.bands.push_back(
              {colorValue(b["color"], wb, "color", false), b["height_m"].as<double>()});
        }
        has_bands = true;
      } else {
        throw std::runtime_error(w + "unknown landmark key '" + key +
                                 "' (name, x_m, y_m, radius_m, bands)");
      }
    } catch (const YAML::Exception& e) {
      throw std::runtime_error(w + "bad value for landmark key '" + key + "': " + e.msg);
    }
  }
  if (!has_x || !has_y) throw std::runtime_error(where + "a landmark needs x_m and y_m");
  if (!has_bands || l.bands.empty())
    throw std::runtime_error(where + "landmark '" + l.name + "' has no bands");
  return l;
}

}  // namespace

FieldDimensions FieldMap::parseYaml(const std::string& text, const std::string& source) {
  const YAML::Node root = io::parseYamlText(text, source);
  FieldDimensions d;
  // Keys left out keep their defaults, but a file without any (empty, or only comments) is a
  // mistake.
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
      {"goal_area_depth_m", &d.goal_area_depth_m},
      {"goal_area_width_m", &d.goal_area_width_m},
      {"penalty_mark_distance_m", &d.penalty_mark_distance_m},
      {"mark_size_m", &d.mark_size_m},
      {"wall_height_m", &d.wall_height_m},
      {"goal_width_m", &d.goal_width_m},
      {"goal_depth_m", &d.goal_depth_m},
      {"goal_height_m", &d.goal_height_m},
      {"goal_post_diameter_m", &d.goal_post_diameter_m},
      {"ball_radius_m", &d.ball_radius_m},
  };
  std::map<std::string, bool*> flags = {{"ball_enabled", &d.ball_enabled},
                                        {"centre_mark", &d.centre_mark}};
  std::map<std::string, std::pair<ColorClass*, bool>> colors = {
      {"goal_color_minus_x", {&d.goal_color_minus_x, false}},
      {"goal_color_plus_x", {&d.goal_color_plus_x, false}},
      {"goal_net_color", {&d.goal_net_color, true}},
      {"ball_color", {&d.ball_color, false}},
  };
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>();
    const std::string where = at(source, kv.first);
    try {
      if (auto it = numbers.find(key); it != numbers.end()) {
        *it->second = kv.second.as<double>();
      } else if (auto f = flags.find(key); f != flags.end()) {
        *f->second = kv.second.as<bool>();
      } else if (auto c = colors.find(key); c != colors.end()) {
        *c->second.first = colorValue(kv.second, where, key, c->second.second);
      } else if (key == "ball_xy_m") {
        const auto v = kv.second.as<std::vector<double>>();
        if (v.size() != 2) throw std::runtime_error(where + "ball_xy_m needs two numbers [x, y]");
        d.ball_xy_m = {v[0], v[1]};
      } else if (key == "landmarks") {
        if (!kv.second.IsSequence() && !kv.second.IsNull())
          throw std::runtime_error(where + "landmarks is a list (empty: [])");
        d.landmarks.clear();
        for (const auto& l : kv.second) d.landmarks.push_back(landmarkValue(l, source));
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
