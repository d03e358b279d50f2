#pragma once
// The indoor-scene world of the place-recognition simulator (simulate_indoor): a building of named
// places (axis-aligned rectangles), walls with heights, windows, furniture boxes and a route, from
// YAML (config/worlds/indoor_building.yaml). Surfaces are textured procedurally from each place's
// style; the building is the same in every run, only the lighting and the noise change with the
// seed.
//
// Frames: `map`, x east, y north, z up, metres.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace adaptive_perception::sim {

enum class FloorPattern { kCarpet, kTiles, kWood, kConcrete, kAsphalt, kGrass };

/// How a place looks. Colours are linear RGB albedos in [0, 1].
struct PlaceStyle {
  Eigen::Vector3d wall_rgb{0.75, 0.74, 0.70};
  Eigen::Vector3d floor_rgb{0.35, 0.35, 0.38};
  FloorPattern floor_pattern = FloorPattern::kCarpet;
  // Chance that a 1 m stretch of wall carries each decoration (the rest stays plain).
  double poster = 0.15;                      // a framed poster at eye height, random colours
  double shelf = 0.0;                        // a bookshelf, rows of coloured spines
  double cabinet = 0.0;                      // kitchen-style cabinets: lower and upper units
  double board = 0.0;                        // a white board with coloured marks
  double machine = 0.0;                      // a grey machine (printer, copier) with a display
  double lamp_color_temperature_k = 3500.0;  // its ceiling lights
  double lamp_intensity = 1.0;               // relative
};

struct IndoorPlace {
  std::string name;
  bool outdoor = false;  // no ceiling: sky above, daylight everywhere
  Eigen::Vector2d min_m{0, 0}, max_m{1, 1};
  PlaceStyle style;
  bool contains(const Eigen::Vector2d& p) const {
    return p.x() >= min_m.x() && p.x() <= max_m.x() && p.y() >= min_m.y() && p.y() <= max_m.y();
  }
};

struct IndoorWall {
  Eigen::Vector2d a_m, b_m;
  double height_m = 2.6;
};

/// A window opening in a wall: between two points on it and two heights.
struct IndoorWindow {
  Eigen::Vector2d a_m, b_m;
  double bottom_m = 0.9, top_m = 2.2;
};

/// A box of furniture standing on the floor.
struct IndoorBox {
  Eigen::Vector2d min_m, max_m;
  double height_m = 0.75;
  Eigen::Vector3d rgb{0.5, 0.4, 0.3};
};

struct RouteStop {
  Eigen::Vector2d xy_m;
  bool spin = false;  // turn a full circle here (look around the place)
};

struct IndoorWorld {
  std::string name;
  double ceiling_m = 2.6;
  std::vector<IndoorPlace> places;
  std::vector<IndoorWall> walls;
  std::vector<IndoorWindow> windows;
  std::vector<IndoorBox> boxes;
  std::vector<RouteStop> route;  // driven once, in order
  double speed_mps = 0.4;
  double turn_rate_radps = 0.6;
  Eigen::Vector3d ground_rgb{0.22, 0.30, 0.15};  // outside every place (lawn)

  /// The place containing p (the first listed when they touch), or -1.
  int placeAt(const Eigen::Vector2d& p) const;
  /// Index of a place by name, or -1.
  int placeIndex(const std::string& name) const;
  /// Adjacency as the route shows it: two places are adjacent when the route passes straight from
  /// one into the other (sampled every 5 cm). Symmetric, sorted lists.
  std::vector<std::vector<int>> adjacency() const;

  /// Loads the YAML world. Keys: name, ceiling_m, speed_mps, turn_rate_radps, places: [{name,
  /// outdoor, min: [x, y], max: [x, y], wall_rgb, floor_rgb, floor: carpet|tiles|wood|concrete|
  /// asphalt|grass, poster, shelf, cabinet, board, machine, lamp_k, lamp_intensity}], walls:
  /// [{points: [[x, y], ...], height_m}], windows: [{from: [x, y], to: [x, y], bottom_m, top_m}],
  /// boxes: [{min: [x, y], max: [x, y], height_m, rgb}], route: [{xy: [x, y], spin: bool}].
  /// Throws std::runtime_error naming the file, the line and what is wrong.
  static IndoorWorld loadYaml(const std::string& path);
};

}  // namespace adaptive_perception::sim
