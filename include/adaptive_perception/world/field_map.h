#pragma once
// 3-D map of a RoboCup soccer field, in the `map` frame: origin at the centre spot, x along the
// long axis (towards the cyan goal on the four-legged field), y to the left when facing +x, z up;
// metres.
//
// Any field is data: FieldDimensions holds the league's dimensions, its goals (coloured panels, or
// round posts with a crossbar and an optional net) and its landmarks as a list (a cylinder with
// coloured bands from the bottom up). config/field_4legged.yaml (the default, the 2005 Sony
// four-legged field), config/field_spl.yaml (the 2024 Standard Platform League field) and
// config/field_spl_landmarks.yaml (SPL plus six four-legged landmarks) are the shipped fields.
//
// The map is built from a FieldDimensions into a few kinds of primitive that the label renderer
// intersects:
//   - the carpet: the plane z = 0 inside |x| <= carpet_half_length_m, |y| <= carpet_half_width_m;
//   - paint on the carpet: axis-aligned rectangles (lines) and rings (centre circle);
//   - vertical quads: field walls, goal panels, crossbars and nets (a segment in the plane times a
//   height range);
//   - vertical cylinders in coloured bands: the landmarks (beacons) and round goal posts;
//   - spheres: the ball.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
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
  SurfaceKind kind = SurfaceKind::kBeacon;  // kGoal for a goal post
};

/// One band of a landmark, listed from the bottom up.
struct LandmarkBand {
  ColorClass color;
  double height_m;
};

/// A cylindrical landmark standing on the carpet (a four-legged-league beacon).
struct Landmark {
  std::string name;  // empty: named after its bands, top first ("pink_over_yellow")
  Eigen::Vector2d xy_m{0.0, 0.0};
  double radius_m = 0.05;
  std::vector<LandmarkBand> bands;  // bottom to top; at least one
};

/// The four beacons of the 2005 four-legged field (the default landmarks): 100 mm across, a 200 mm
/// white base and two 100 mm bands, at x = +-1.35, y = +-1.95 m. Looking from the yellow goal (-x)
/// to the cyan goal (+x): on the right (-y) the top band is pink and the lower band has the colour
/// of the nearer goal; on the left (+y) it is the other way round.
std::vector<Landmark> fourLeggedBeacons();

struct Sphere {
  Eigen::Vector3d centre_m;
  double radius_m;
  ColorClass color;
};

/// A field's description; defaults are the 2005 Sony four-legged-league field (see
/// config/field_4legged.yaml). YAML keys are the member names.
struct FieldDimensions {
  double field_length_m = 5.4;             // between the goal lines (outer edges)
  double field_width_m = 3.6;              // between the side lines (outer edges)
  double carpet_margin_m = 0.3;            // green carpet beyond the lines (to the wall, if any)
  double line_width_m = 0.025;             // every painted line
  double centre_circle_diameter_m = 0.36;  // to the middle of the line
  double penalty_area_depth_m = 0.65;      // from the goal line into the field
  double penalty_area_width_m = 1.3;
  double goal_area_depth_m = 0.0;  // the smaller box in front of each goal; 0: none
  double goal_area_width_m = 0.0;
  double penalty_mark_distance_m = 0.0;  // goal line (outer edge) to the mark's centre; 0: none
  double mark_size_m = 0.1;              // the arms of the penalty and centre marks (crosses)
  bool centre_mark = false;              // a cross on the centre spot
  double wall_height_m = 0.1;            // white field wall around the carpet; 0: no wall
  double goal_width_m = 0.8;             // inner width of the goal mouth
  double goal_depth_m = 0.3;
  double goal_height_m = 0.3;
  /// 0: each goal is three coloured panels (the four-legged goal). Otherwise two round posts of
  /// this diameter, a crossbar as deep, and the net (if goal_net_color is set) behind.
  double goal_post_diameter_m = 0.0;
  ColorClass goal_color_minus_x = kYellow;  // the goal behind -x (panels, or posts and crossbar)
  ColorClass goal_color_plus_x = kCyan;
  ColorClass goal_net_color = kBackground;  // kBackground (YAML "none"): an open net, not drawn
  std::vector<Landmark> landmarks = fourLeggedBeacons();
  bool ball_enabled = false;
  Eigen::Vector2d ball_xy_m{0.0, 0.0};
  double ball_radius_m = 0.043;
  ColorClass ball_color = kOrange;

  /// Throws std::invalid_argument naming the first bad field (non-positive size, goal wider than
  /// the field...).
  void validate() const;
};

class FieldMap {
 public:
  FieldMap() : FieldMap(FieldDimensions{}) {}
  explicit FieldMap(const FieldDimensions& dims);

  /// Loads a field from YAML (keys as in FieldDimensions; missing keys keep defaults; `landmarks`
  /// is a list of {name, x_m, y_m, radius_m, bands: [{color, height_m}, ...]}, colours by name).
  /// Throws std::runtime_error with the file name and line on a missing/bad file, an unknown key,
  /// a landmark without bands or an invalid value.
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
  // groundColorAt's index: the carpet cut into square cells; per cell, the paint (rects first,
  // then rings, each in its list's order; a ring's index offset by rects_.size()) whose bounding
  // box touches the cell, so that a lookup tests a few shapes instead of all of them and still
  // answers as the scan over all of them would.
  void indexGround();
  double ground_cell_m_ = 0.25;  // set by indexGround
  int ground_cols_ = 0, ground_rows_ = 0;
  std::vector<int> ground_begin_;  // cell c's shapes: ground_shapes_[begin[c], begin[c + 1])
  std::vector<int> ground_shapes_;
  std::vector<VerticalQuad> quads_;
  std::vector<Cylinder> cylinders_;
  std::vector<Sphere> spheres_;
};

// Inline: the renderer calls it for every pixel that sees the carpet.
inline ColorClass FieldMap::groundColorAt(double x, double y) const {
  if (!(std::fabs(x) <= carpet_half_length_m_ && std::fabs(y) <= carpet_half_width_m_))
    return kBackground;
  const int cx = std::clamp(static_cast<int>((x + carpet_half_length_m_) / ground_cell_m_), 0,
                            ground_cols_ - 1);
  const int cy = std::clamp(static_cast<int>((y + carpet_half_width_m_) / ground_cell_m_), 0,
                            ground_rows_ - 1);
  const size_t cell = static_cast<size_t>(cy) * ground_cols_ + cx;
  const int nr = static_cast<int>(rects_.size());
  for (int k = ground_begin_[cell]; k < ground_begin_[cell + 1]; ++k) {
    const int i = ground_shapes_[k];
    if (i < nr) {
      const GroundRect& g = rects_[i];
      if (x >= g.x0_m && x <= g.x1_m && y >= g.y0_m && y <= g.y1_m) return g.color;
    } else {
      const GroundRing& g = rings_[i - nr];
      const double r2 = (x - g.cx_m) * (x - g.cx_m) + (y - g.cy_m) * (y - g.cy_m);
      if (r2 >= g.r_inner_m * g.r_inner_m && r2 <= g.r_outer_m * g.r_outer_m) return g.color;
    }
  }
  return kGreen;
}

}  // namespace adaptive_perception::world
