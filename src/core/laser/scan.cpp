#include "adaptive_perception/laser/scan.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace adaptive_perception::laser {

std::string scanGeometryProblem(const LaserScan2D& scan) {
  std::ostringstream why;
  const double last_bearing = scan.ranges_m.empty()
                                  ? scan.angle_min_rad
                                  : scan.bearing(static_cast<int>(scan.ranges_m.size()) - 1);
  if (!std::isfinite(scan.angle_min_rad))
    why << "angle_min " << scan.angle_min_rad << " is not finite";
  else if (!std::isfinite(scan.angle_increment_rad) || scan.angle_increment_rad == 0.0)
    why << "angle_increment " << scan.angle_increment_rad << " is not a finite non-zero angle";
  else if (!std::isfinite(last_bearing))
    why << "the last beam's bearing " << last_bearing << " is not finite";
  else if (!(scan.range_max_m > 0.0))
    why << "range_max " << scan.range_max_m << " is not above zero";
  else if (std::isnan(scan.range_min_m))
    why << "range_min is NaN";
  return why.str();
}

int validPoints(const LaserScan2D& scan, double min_range_m, std::vector<ScanPoint>* out) {
  out->clear();
  const double lo = std::max(scan.range_min_m, min_range_m);
  int dropped = 0;
  for (int i = 0; i < static_cast<int>(scan.ranges_m.size()); ++i) {
    const double r = scan.ranges_m[i];
    if (!std::isfinite(r) || r < lo || r >= scan.range_max_m) {
      ++dropped;
      continue;
    }
    const double b = scan.bearing(i);
    if (!std::isfinite(b)) {
      ++dropped;
      continue;
    }
    out->push_back({Eigen::Vector2d(r * std::cos(b), r * std::sin(b)), r, b, i});
  }
  return dropped;
}

}  // namespace adaptive_perception::laser
