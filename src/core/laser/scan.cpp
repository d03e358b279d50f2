#include "adaptive_perception/laser/scan.h"

#include <algorithm>
#include <cmath>

namespace adaptive_perception::laser {

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
    out->push_back({Eigen::Vector2d(r * std::cos(b), r * std::sin(b)), r, b, i});
  }
  return dropped;
}

}  // namespace adaptive_perception::laser
