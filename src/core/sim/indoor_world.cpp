#include "adaptive_perception/sim/indoor_world.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "adaptive_perception/io/yaml_file.h"

namespace adaptive_perception::sim {

int IndoorWorld::placeAt(const Eigen::Vector2d& p) const {
  for (size_t i = 0; i < places.size(); ++i)
    if (places[i].contains(p)) return static_cast<int>(i);
  return -1;
}

int IndoorWorld::placeIndex(const std::string& n) const {
  for (size_t i = 0; i < places.size(); ++i)
    if (places[i].name == n) return static_cast<int>(i);
  return -1;
}

std::vector<std::vector<int>> IndoorWorld::adjacency() const {
  std::vector<std::set<int>> adj(places.size());
  int prev = -1;
  for (size_t k = 0; k + 1 < route.size(); ++k) {
    const Eigen::Vector2d a = route[k].xy_m, b = route[k + 1].xy_m;
    const int steps = std::max(1, static_cast<int>((b - a).norm() / 0.05));
    for (int s = 0; s <= steps; ++s) {
      const int p = placeAt(a + (b - a) * (static_cast<double>(s) / steps));
      if (p >= 0 && prev >= 0 && p != prev) {
        adj[p].insert(prev);
        adj[prev].insert(p);
      }
      if (p >= 0) prev = p;
    }
  }
  std::vector<std::vector<int>> out;
  for (const auto& s : adj) out.emplace_back(s.begin(), s.end());
  return out;
}

IndoorWorld IndoorWorld::loadYaml(const std::string& path) {
  const YAML::Node root = io::loadYamlFile(path, "world file");
  auto where = [&](const YAML::Node& n) { return io::yamlWhere(path, n); };
  auto vec2 = [&](const YAML::Node& n, const char* what) {
    if (!n) throw std::runtime_error(path + ": missing " + std::string(what));
    const auto v = n.as<std::vector<double>>();
    if (v.size() != 2) throw std::runtime_error(where(n) + ": " + what + " is [x, y]");
    return Eigen::Vector2d(v[0], v[1]);
  };
  auto rgb = [&](const YAML::Node& n, const Eigen::Vector3d& def) {
    if (!n) return def;
    const auto v = n.as<std::vector<double>>();
    if (v.size() != 3 || *std::min_element(v.begin(), v.end()) < 0.0 ||
        *std::max_element(v.begin(), v.end()) > 1.0)
      throw std::runtime_error(where(n) + ": a colour is [r, g, b] with each in [0, 1]");
    return Eigen::Vector3d(v[0], v[1], v[2]);
  };
  IndoorWorld w;
  try {
    w.name = root["name"] ? root["name"].as<std::string>() : path;
    if (root["ceiling_m"]) w.ceiling_m = root["ceiling_m"].as<double>();
    if (root["speed_mps"]) w.speed_mps = root["speed_mps"].as<double>();
    if (root["turn_rate_radps"]) w.turn_rate_radps = root["turn_rate_radps"].as<double>();
    if (!(w.ceiling_m > 1.0) || !(w.speed_mps > 0.0) || !(w.turn_rate_radps > 0.0))
      throw std::runtime_error(path +
                               ": ceiling_m must exceed 1, speed_mps and turn_rate_radps "
                               "must be positive");
    if (!root["places"] || !root["walls"] || !root["route"])
      throw std::runtime_error(path + ": needs `places`, `walls` and `route`");
    for (const auto& n : root["places"]) {
      IndoorPlace p;
      if (!n["name"]) throw std::runtime_error(where(n) + ": a place needs a name");
      p.name = n["name"].as<std::string>();
      if (w.placeIndex(p.name) >= 0)
        throw std::runtime_error(where(n) + ": place '" + p.name + "' defined twice");
      p.outdoor = n["outdoor"] && n["outdoor"].as<bool>();
      p.min_m = vec2(n["min"], "min");
      p.max_m = vec2(n["max"], "max");
      if (!(p.max_m.x() > p.min_m.x() && p.max_m.y() > p.min_m.y()))
        throw std::runtime_error(where(n) + ": place '" + p.name + "' needs max > min");
      PlaceStyle& s = p.style;
      s.wall_rgb = rgb(n["wall_rgb"], s.wall_rgb);
      s.floor_rgb = rgb(n["floor_rgb"], s.floor_rgb);
      if (n["floor"]) {
        const std::string f = n["floor"].as<std::string>();
        const std::vector<std::pair<std::string, FloorPattern>> kinds = {
            {"carpet", FloorPattern::kCarpet},   {"tiles", FloorPattern::kTiles},
            {"wood", FloorPattern::kWood},       {"concrete", FloorPattern::kConcrete},
            {"asphalt", FloorPattern::kAsphalt}, {"grass", FloorPattern::kGrass}};
        const auto it =
            std::find_if(kinds.begin(), kinds.end(), [&](const auto& k) { return k.first == f; });
        if (it == kinds.end())
          throw std::runtime_error(where(n["floor"]) + ": floor '" + f +
                                   "' is not one of carpet, tiles, wood, concrete, asphalt, grass");
        s.floor_pattern = it->second;
      }
      for (auto [key, field] : {std::pair{"poster", &s.poster}, std::pair{"shelf", &s.shelf},
                                std::pair{"cabinet", &s.cabinet}, std::pair{"board", &s.board},
                                std::pair{"machine", &s.machine}}) {
        if (!n[key]) continue;  // keep the default
        *field = n[key].as<double>();
        if (!(*field >= 0.0 && *field <= 1.0))
          throw std::runtime_error(where(n[key]) + ": " + key + " is a probability in [0, 1]");
      }
      const double deco = s.poster + s.shelf + s.cabinet + s.board + s.machine;
      if (deco > 1.0)
        throw std::runtime_error(where(n) + ": place '" + p.name +
                                 "': the decoration chances add up to more than 1");
      if (n["lamp_k"]) s.lamp_color_temperature_k = n["lamp_k"].as<double>();
      if (n["lamp_intensity"]) s.lamp_intensity = n["lamp_intensity"].as<double>();
      if (!(s.lamp_color_temperature_k >= 1500.0 && s.lamp_color_temperature_k <= 12000.0))
        throw std::runtime_error(where(n) + ": lamp_k must be in [1500, 12000]");
      w.places.push_back(p);
    }
    if (w.places.empty()) throw std::runtime_error(path + ": no place");
    for (const auto& n : root["walls"]) {
      if (!n["points"]) throw std::runtime_error(where(n) + ": a wall needs `points`");
      std::vector<Eigen::Vector2d> pts;
      for (const auto& q : n["points"]) pts.push_back(vec2(q, "a wall point"));
      if (pts.size() < 2) throw std::runtime_error(where(n) + ": a wall needs two points");
      const double h = n["height_m"] ? n["height_m"].as<double>() : w.ceiling_m;
      if (!(h > 0.0)) throw std::runtime_error(where(n) + ": height_m must be positive");
      for (size_t k = 0; k + 1 < pts.size(); ++k) w.walls.push_back({pts[k], pts[k + 1], h});
    }
    if (root["windows"])
      for (const auto& n : root["windows"]) {
        IndoorWindow win;
        win.a_m = vec2(n["from"], "from");
        win.b_m = vec2(n["to"], "to");
        if (n["bottom_m"]) win.bottom_m = n["bottom_m"].as<double>();
        if (n["top_m"]) win.top_m = n["top_m"].as<double>();
        if (!(win.top_m > win.bottom_m && win.bottom_m >= 0.0))
          throw std::runtime_error(where(n) + ": a window needs 0 <= bottom_m < top_m");
        w.windows.push_back(win);
      }
    if (root["boxes"])
      for (const auto& n : root["boxes"]) {
        IndoorBox b;
        b.min_m = vec2(n["min"], "min");
        b.max_m = vec2(n["max"], "max");
        if (n["height_m"]) b.height_m = n["height_m"].as<double>();
        b.rgb = rgb(n["rgb"], b.rgb);
        if (!(b.max_m.x() > b.min_m.x() && b.max_m.y() > b.min_m.y() && b.height_m > 0.0))
          throw std::runtime_error(where(n) + ": a box needs max > min and a positive height");
        w.boxes.push_back(b);
      }
    for (const auto& n : root["route"]) {
      RouteStop s;
      s.xy_m = vec2(n["xy"], "xy");
      s.spin = n["spin"] && n["spin"].as<bool>();
      w.route.push_back(s);
    }
    if (w.route.size() < 2) throw std::runtime_error(path + ": the route needs two stops");
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(path + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  return w;
}

}  // namespace adaptive_perception::sim
