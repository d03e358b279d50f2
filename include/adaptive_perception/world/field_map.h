#pragma once
// 3-D map of a Sony four-legged-league soccer field, in the `map` frame: origin at the centre spot,
// x towards the cyan (sky-blue) goal, y to the left when facing it, z up; metres.
//
// The map is built from league dimensions (FieldDimensions, loaded from config/field_4legged.yaml)
// into a few kinds of primitive that the label renderer intersects:
//   - the carpet: the plane z = 0 inside |x| <= carpet_half_length_m, |y| <= carpet_half_width_m;
//   - paint on the carpet: axis-aligned rectangles (lines) and rings (centre circle);
//   - vertical quads: field walls and the goal panels (a segment in the plane times a height
//   range);
//   - vertical cylinders in coloured bands: the beacons;
//   - spheres: the ball.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::world {

/// Which part of the field a surface is; the simulator gives each its own material.
enum class SurfaceKind : std::uint8_t { kNone, kCarpet, kLine, kWall, kGoal, kBeacon, kBall };

struct GroundRect {  // paint: x0 <= x <= x1, y0 <= y <= y1 on z = 0
  double x0_m, y0_m, x1_m, y1_m;
  ColorClass color;
};

struct GroundRing {  // paint: r_inner <= |(x,y) - centre| <= r_outer on z = 0
  double cx_m, cy_m, r_inner_m, r_outer_m;
  ColorClass color;
};

struct VerticalQuad {  // the segment p0 -> p1 on the ground swept from z0 to z1
  Eigen::Vector2d p0_m, p1_m;
  double z0_m, z1_m;
  ColorClass color;
  SurfaceKind kind;
};

struct CylinderBand {
  double z0_m, z1_m;
  ColorClass color;
};

struct Cylinder {  // vertical cylinder, axis through (cx, cy)
  double cx_m, cy_m, radius_m;
  std::vector<CylinderBand> bands;  // bottom to top, contiguous
  std::string name;
};

struct Sphere {
  Eigen::Vector3d centre_m;
  double radius_m;
  ColorClass color;
};

/// League dimensions; defaults are the 2005 Sony four-legged-league field (see
/// config/field_4legged.yaml).
struct FieldDimensions {
  double field_length_m = 5.4;             // between the goal lines (outer edges)
  double field_width_m = 3.6;              // between the side lines (outer edges)
  double carpet_margin_m = 0.3;            // green carpet beyond the lines up to the field wall
  double line_width_m = 0.025;             // every painted line
  double centre_circle_diameter_m = 0.36;  // to the middle of the line
  double penalty_area_depth_m = 0.65;      // from the goal line into the field
  double penalty_area_width_m = 1.3;
  double wall_height_m = 0.1;  // white field wall around the carpet
  double goal_width_m = 0.8;   // inner width of the goal mouth
  double goal_depth_m = 0.3;
  double goal_height_m = 0.3;
  double beacon_x_m = 1.35;  // |x| of the beacons (from the halfway line)
  double beacon_y_m = 1.95;  // |y| of the beacon axes
  double beacon_radius_m = 0.05;
  double beacon_white_height_m = 0.2;  // white base (part C)
  double beacon_band_height_m = 0.1;   // each coloured band (parts B and A)
  bool ball_enabled = false;
  Eigen::Vector2d ball_xy_m{0.0, 0.0};
  double ball_radius_m = 0.043;

  /// Throws std::invalid_argument naming the first bad field (non-positive size, goal wider than
  /// the field...).
  void validate() const;
};

class FieldMap {
 public:
  FieldMap() : FieldMap(FieldDimensions{}) {}
  explicit FieldMap(const FieldDimensions& dims);

  /// Loads dimensions from YAML (keys as in FieldDimensions; missing keys keep defaults). Throws
  /// std::runtime_error with the file name (and line, for syntax errors) on a missing/bad file, an
  /// unknown key or an invalid value.
  static FieldMap loadYaml(const std::string& path);
  static FieldDimensions parseYaml(const std::string& yaml_text, const std::string& source_name);

  const FieldDimensions& dimensions() const { return dims_; }
  double carpetHalfLength() const { return carpet_half_length_m_; }
  double carpetHalfWidth() const { return carpet_half_width_m_; }
  const std::vector<GroundRect>& groundRects() const { return rects_; }
  const std::vector<GroundRing>& groundRings() const { return rings_; }
  const std::vector<VerticalQuad>& quads() const { return quads_; }
  const std::vector<Cylinder>& cylinders() const { return cylinders_; }
  const std::vector<Sphere>& spheres() const { return spheres_; }

  /// The colour of the carpet at (x, y) (green or the paint on it); kBackground outside the carpet.
  ColorClass groundColorAt(double x_m, double y_m) const;
  /// True when (x, y) is a place a robot can stand: on the carpet, outside goals and beacons, with
  /// a margin.
  bool isFree(double x_m, double y_m, double margin_m) const;

 private:
  FieldDimensions dims_;
  double carpet_half_length_m_ = 0.0, carpet_half_width_m_ = 0.0;
  std::vector<GroundRect> rects_;
  std::vector<GroundRing> rings_;
  std::vector<VerticalQuad> quads_;
  std::vector<Cylinder> cylinders_;
  std::vector<Sphere> spheres_;
};

}  // namespace adaptive_perception::world
