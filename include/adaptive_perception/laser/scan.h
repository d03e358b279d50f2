#pragma once
// A planar laser scan in the core's own terms (no ROS): ranges at evenly spaced bearings in the
// laser frame.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace adaptive_perception::laser {

struct LaserScan2D {
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;
  double range_min_m = 0.0;
  double range_max_m = 0.0;
  std::vector<float> ranges_m;

  double bearing(int i) const { return angle_min_rad + i * angle_increment_rad; }
};

/// Why a scan's geometry cannot be used, or "" when it can: angle_min and angle_increment finite,
/// the increment non-zero, every beam's bearing finite, range_max above zero (+inf: no limit) and
/// range_min not NaN, each named with its value. The nodes refuse a scan with a problem
/// (line_extractor, ekf_slam_mapper); validPoints() alone would drop its beams one by one.
std::string scanGeometryProblem(const LaserScan2D& scan);

/// A valid return: Cartesian point in the laser frame plus where it came from.
struct ScanPoint {
  Eigen::Vector2d p_m;
  double range_m;
  double bearing_rad;
  int beam;  // index into the scan
};

/// The valid returns of a scan: finite, >= max(range_min, min_range_m) and < range_max (a max-range
/// reading is "no return", not a wall), at a finite bearing. Returns the number of beams dropped.
int validPoints(const LaserScan2D& scan, double min_range_m, std::vector<ScanPoint>* out);

}  // namespace adaptive_perception::laser
