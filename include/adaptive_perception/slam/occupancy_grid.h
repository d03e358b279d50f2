#pragma once
// An occupancy grid rendered from laser scans at known laser poses: the map a navigation stack
// uses, in the conventions of nav_msgs/OccupancyGrid without ROS (cells row-major from the
// origin, the pose of cell (0, 0)'s outer corner, x to the right and y up; -1 unknown, 0 free
// .. 100 occupied), and its files in map_server's format (PGM + YAML).
//
// Rendering, GMapping's counting model: each beam walks the cells from the laser to its end
// (Bresenham), counting a visit in every cell it crosses and a visit and a hit in its end cell. A
// return beyond max_range_m visits the cells up to max_range_m and hits none (GMapping's
// maxUrange); a no-return (+inf, >= the scan's range_max) is not used, as in GMapping: it says
// nothing of where the beam went. A cell no beam visited is unknown
// (-1); the others are occupied (100) when more than occupied_fraction of their visits were hits,
// else free (0). The grid spans the poses and every hit, plus margin_m.
#include <cstdint>
#include <string>
#include <vector>

#include "adaptive_perception/laser/scan.h"
#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::slam {

struct OccupancyGridConfig {
  double resolution_m = 0.05;  // cell side, 0.005..10 (the and gmapping's 0.05)
  double max_range_m = 30.0;   // beams are used up to here, > 0
  // GMapping's occ_thresh: a wall cell is also crossed by beams that graze it, so a quarter of
  // hits already marks a wall.
  double occupied_fraction = 0.25;  // in (0, 1)
  double margin_m = 1.0;            // around the poses and hits, >= 0
  long max_cells = 400000000;       // refuse larger grids (a bad pose would make one), >= 1
  void validate() const;            // throws std::invalid_argument naming the bad field
};

struct OccupancyGrid {
  double resolution_m = 0.05;
  double origin_x_m = 0.0, origin_y_m = 0.0;  // the lower-left corner of cell (0, 0)
  int width = 0, height = 0;
  std::vector<std::int8_t> data;  // height rows of width cells, row 0 at origin_y_m

  std::int8_t at(int x, int y) const { return data[static_cast<size_t>(y) * width + x]; }
  /// The cell holding a point (false when it lies outside).
  bool cellOf(double x_m, double y_m, int* x, int* y) const;
};

/// The grid of `scans`, scan i seen from laser pose `laser_poses[i]` in the map frame. Throws
/// std::invalid_argument on different counts, no scan, a bad config, or a grid of more than
/// max_cells.
OccupancyGrid renderOccupancyGrid(const std::vector<laser::LaserScan2D>& scans,
                                  const std::vector<math::SE2>& laser_poses,
                                  const OccupancyGridConfig& config = {});

/// The scans a live map is rendered from (the mapper node): a scan is kept when the laser moved at
/// least min_distance_m or turned min_angle_rad since the last kept one, as GMapping updates its
/// map only after linearUpdate / angularUpdate of motion; scans in between add little but time.
class GridKeyframes {
 public:
  explicit GridKeyframes(double min_distance_m = 0.1, double min_angle_rad = 0.1);
  /// Keeps the scan (true) or not (false). Throws std::invalid_argument on a non-finite pose.
  bool add(const laser::LaserScan2D& scan, const math::SE2& laser_pose);
  size_t size() const { return scans_.size(); }
  const std::vector<laser::LaserScan2D>& scans() const { return scans_; }
  const std::vector<math::SE2>& poses() const { return poses_; }
  void clear();

 private:
  double min_distance_m_, min_angle_rad_;
  std::vector<laser::LaserScan2D> scans_;
  std::vector<math::SE2> poses_;
};

/// Writes the grid as map_server reads it: `yaml_path` (image, resolution, origin, negate 0,
/// occupied_thresh, free_thresh, mode trinary) and the PGM beside it (the YAML's name with .pgm;
/// binary P5, row 0 the top of the map: occupied 0, free 254, unknown 205, with map_saver's
/// thresholds 0.65 and 0.196, which read those values back as they were). Each file is written to
/// a temporary file and renamed (an existing file is replaced whole or not at all). Throws
/// std::runtime_error naming the file that cannot be written.
void writeMapServerFiles(const OccupancyGrid& grid, const std::string& yaml_path);

/// Reads a map_server YAML and its image (PGM; any image OpenCV reads), as map_server does: p =
/// (255 - value) / 255 (or value / 255 with negate 1), p > occupied_thresh is 100, p <
/// free_thresh is 0, the rest -1. Throws std::runtime_error naming the file and the key or value
/// that is wrong.
OccupancyGrid readMapServerFiles(const std::string& yaml_path);

}  // namespace adaptive_perception::slam
