#include "adaptive_perception/slam/occupancy_grid.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "adaptive_perception/io/atomic_file.h"
#include "adaptive_perception/math/angles.h"

namespace adaptive_perception::slam {
namespace {

void need(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("OccupancyGridConfig: " + what);
}

}  // namespace

void OccupancyGridConfig::validate() const {
  need(resolution_m >= 0.005 && resolution_m <= 10.0, "resolution_m must be in [0.005, 10]");
  need(max_range_m > 0.0 && std::isfinite(max_range_m), "max_range_m must be > 0");
  need(occupied_fraction > 0.0 && occupied_fraction < 1.0, "occupied_fraction must be in (0, 1)");
  need(margin_m >= 0.0 && std::isfinite(margin_m), "margin_m must be >= 0");
  need(max_cells >= 1, "max_cells must be >= 1");
}

bool OccupancyGrid::cellOf(double x_m, double y_m, int* x, int* y) const {
  const double fx = std::floor((x_m - origin_x_m) / resolution_m);
  const double fy = std::floor((y_m - origin_y_m) / resolution_m);
  if (!(fx >= 0 && fy >= 0 && fx < width && fy < height)) return false;
  *x = static_cast<int>(fx);
  *y = static_cast<int>(fy);
  return true;
}

OccupancyGrid renderOccupancyGrid(const std::vector<laser::LaserScan2D>& scans,
                                  const std::vector<math::SE2>& laser_poses,
                                  const OccupancyGridConfig& config) {
  config.validate();
  if (scans.size() != laser_poses.size())
    throw std::invalid_argument("renderOccupancyGrid: " + std::to_string(scans.size()) +
                                " scans for " + std::to_string(laser_poses.size()) + " poses");
  if (scans.empty()) throw std::invalid_argument("renderOccupancyGrid: no scan");
  // A beam's end in the map frame and whether it is a hit.
  const auto end = [&](const laser::LaserScan2D& s, const math::SE2& pose, int i, bool* hit) {
    const float r = s.ranges_m[i];
    const double limit = std::min(config.max_range_m, s.range_max_m > 0 ? s.range_max_m : 1e9);
    *hit = std::isfinite(r) && r >= s.range_min_m && r < limit;
    const bool no_return = !std::isfinite(r) || (s.range_max_m > 0 && r >= s.range_max_m);
    // A no-return says nothing of where the beam went (glass, a dark surface, a dropout): it is
    // not used, as in GMapping. A return beyond max_range_m clears up to there.
    const double used = *hit ? r : (!no_return && r >= limit ? config.max_range_m : -1.0);
    if (used < 0.0) return Eigen::Vector2d(std::nan(""), 0.0);  // unused
    const double b = s.bearing(i);
    return pose.transformPoint(Eigen::Vector2d(used * std::cos(b), used * std::sin(b)));
  };
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  const auto grow = [&](const Eigen::Vector2d& p) {
    lo_x = std::min(lo_x, p.x());
    lo_y = std::min(lo_y, p.y());
    hi_x = std::max(hi_x, p.x());
    hi_y = std::max(hi_y, p.y());
  };
  for (size_t k = 0; k < scans.size(); ++k) {
    grow(Eigen::Vector2d(laser_poses[k].x_m, laser_poses[k].y_m));
    for (int i = 0; i < static_cast<int>(scans[k].ranges_m.size()); ++i) {
      bool hit = false;
      const Eigen::Vector2d e = end(scans[k], laser_poses[k], i, &hit);
      if (hit) grow(e);
    }
  }
  OccupancyGrid g;
  g.resolution_m = config.resolution_m;
  g.origin_x_m = lo_x - config.margin_m;
  g.origin_y_m = lo_y - config.margin_m;
  const double w = std::ceil((hi_x + config.margin_m - g.origin_x_m) / g.resolution_m);
  const double h = std::ceil((hi_y + config.margin_m - g.origin_y_m) / g.resolution_m);
  if (!(w * h <= static_cast<double>(config.max_cells)))
    throw std::invalid_argument("renderOccupancyGrid: the poses and hits span " +
                                std::to_string(hi_x - lo_x) + " x " + std::to_string(hi_y - lo_y) +
                                " m, more than max_cells cells at this resolution");
  g.width = std::max(1, static_cast<int>(w));
  g.height = std::max(1, static_cast<int>(h));
  std::vector<std::uint32_t> visits(static_cast<size_t>(g.width) * g.height, 0), hits(visits);
  // Cell coordinates of a point, unclipped.
  const auto cell = [&](const Eigen::Vector2d& p) {
    return std::pair<long, long>(
        static_cast<long>(std::floor((p.x() - g.origin_x_m) / g.resolution_m)),
        static_cast<long>(std::floor((p.y() - g.origin_y_m) / g.resolution_m)));
  };
  for (size_t k = 0; k < scans.size(); ++k) {
    const auto [x0, y0] = cell(Eigen::Vector2d(laser_poses[k].x_m, laser_poses[k].y_m));
    for (int i = 0; i < static_cast<int>(scans[k].ranges_m.size()); ++i) {
      bool hit = false;
      const Eigen::Vector2d e = end(scans[k], laser_poses[k], i, &hit);
      if (std::isnan(e.x())) continue;
      const auto [x1, y1] = cell(e);
      // Bresenham from the laser's cell to the end cell; the end cell itself is the hit.
      long x = x0, y = y0;
      const long dx = std::labs(x1 - x0), dy = -std::labs(y1 - y0);
      const long sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
      long err = dx + dy;
      while (!(x == x1 && y == y1)) {
        if (x >= 0 && y >= 0 && x < g.width && y < g.height)
          ++visits[static_cast<size_t>(y) * g.width + x];
        const long e2 = 2 * err;
        if (e2 >= dy) {
          err += dy;
          x += sx;
        }
        if (e2 <= dx) {
          err += dx;
          y += sy;
        }
      }
      if (hit && x1 >= 0 && y1 >= 0 && x1 < g.width && y1 < g.height) {
        ++visits[static_cast<size_t>(y1) * g.width + x1];
        ++hits[static_cast<size_t>(y1) * g.width + x1];
      }
    }
  }
  g.data.assign(visits.size(), -1);
  for (size_t c = 0; c < visits.size(); ++c)
    if (visits[c] > 0) g.data[c] = hits[c] > config.occupied_fraction * visits[c] ? 100 : 0;
  return g;
}

GridKeyframes::GridKeyframes(double min_distance_m, double min_angle_rad)
    : min_distance_m_(min_distance_m), min_angle_rad_(min_angle_rad) {
  if (!(min_distance_m >= 0.0 && min_angle_rad >= 0.0))
    throw std::invalid_argument("GridKeyframes: the motion thresholds must be >= 0");
}

bool GridKeyframes::add(const laser::LaserScan2D& scan, const math::SE2& laser_pose) {
  if (!std::isfinite(laser_pose.x_m) || !std::isfinite(laser_pose.y_m) ||
      !std::isfinite(laser_pose.yaw_rad))
    throw std::invalid_argument("GridKeyframes::add: the laser pose is not finite");
  if (!poses_.empty()) {
    const math::SE2& last = poses_.back();
    const bool moved = std::hypot(laser_pose.x_m - last.x_m, laser_pose.y_m - last.y_m) >=
                           min_distance_m_ ||
                       std::abs(math::angleDiff(laser_pose.yaw_rad, last.yaw_rad)) >= min_angle_rad_;
    if (!moved) return false;
  }
  scans_.push_back(scan);
  poses_.push_back(laser_pose);
  return true;
}

void GridKeyframes::clear() {
  scans_.clear();
  poses_.clear();
}

void writeMapServerFiles(const OccupancyGrid& grid, const std::string& yaml_path) {
  namespace fs = std::filesystem;
  if (grid.width < 1 || grid.height < 1 ||
      grid.data.size() != static_cast<size_t>(grid.width) * grid.height)
    throw std::runtime_error(yaml_path + ": the grid to write is empty or inconsistent");
  const fs::path yaml(yaml_path);
  const fs::path pgm = fs::path(yaml).replace_extension(".pgm");
  if (pgm == yaml) throw std::runtime_error(yaml_path + ": the map's YAML cannot end in .pgm");
  std::string image =
      "P5\n" + std::to_string(grid.width) + " " + std::to_string(grid.height) + "\n255\n";
  const size_t header = image.size();
  image.resize(header + grid.data.size());
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < grid.width; ++x) {
      const std::int8_t v = grid.at(x, y);
      image[header + static_cast<size_t>(grid.height - 1 - y) * grid.width + x] =
          static_cast<char>(v < 0     ? 205
                            : v >= 50 ? 0
                                      : 254);
    }
  char text[512];
  std::snprintf(text, sizeof(text),
                "image: %s\nmode: trinary\nresolution: %.6f\norigin: [%.6f, %.6f, 0.0]\n"
                "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
                pgm.filename().string().c_str(), grid.resolution_m, grid.origin_x_m,
                grid.origin_y_m);
  io::writeTextFileAtomically(pgm.string(), image);
  io::writeTextFileAtomically(yaml.string(), text);
}

OccupancyGrid readMapServerFiles(const std::string& yaml_path) {
  namespace fs = std::filesystem;
  YAML::Node y;
  try {
    y = YAML::LoadFile(yaml_path);
  } catch (const std::exception& e) {
    throw std::runtime_error(yaml_path + ": cannot be read as YAML: " + e.what());
  }
  const auto get = [&](const char* key) {
    if (!y[key])
      throw std::runtime_error(yaml_path + ": the map has no '" + std::string(key) + "'");
    return y[key];
  };
  OccupancyGrid g;
  double occupied = 0.0, free = 0.0;
  int negate = 0;
  std::string image;
  try {
    image = get("image").as<std::string>();
    g.resolution_m = get("resolution").as<double>();
    const YAML::Node origin = get("origin");
    if (!origin.IsSequence() || origin.size() != 3)
      throw std::runtime_error(yaml_path + ": 'origin' must be [x, y, yaw]");
    g.origin_x_m = origin[0].as<double>();
    g.origin_y_m = origin[1].as<double>();
    negate = get("negate").as<int>();
    occupied = get("occupied_thresh").as<double>();
    free = get("free_thresh").as<double>();
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(yaml_path + ": a map value has the wrong type: " + e.what());
  }
  if (!(std::isfinite(g.resolution_m) && g.resolution_m > 0.0))
    throw std::runtime_error(yaml_path + ": 'resolution' must be finite and > 0");
  if (!(std::isfinite(g.origin_x_m) && std::isfinite(g.origin_y_m)))
    throw std::runtime_error(yaml_path + ": 'origin' must be finite");
  if (!(free >= 0.0 && free < occupied && occupied <= 1.0))
    throw std::runtime_error(yaml_path + ": needs 0 <= free_thresh < occupied_thresh <= 1");
  fs::path img_path(image);
  if (img_path.is_relative()) img_path = fs::path(yaml_path).parent_path() / img_path;
  const cv::Mat m = cv::imread(img_path.string(), cv::IMREAD_GRAYSCALE);
  if (m.empty())
    throw std::runtime_error(yaml_path + ": its image '" + img_path.string() + "' cannot be read");
  g.width = m.cols;
  g.height = m.rows;
  g.data.resize(static_cast<size_t>(g.width) * g.height);
  for (int r = 0; r < m.rows; ++r)
    for (int x = 0; x < m.cols; ++x) {
      const double v = m.at<uchar>(r, x);
      const double p = negate ? v / 255.0 : (255.0 - v) / 255.0;
      g.data[static_cast<size_t>(g.height - 1 - r) * g.width + x] = p > occupied ? 100
                                                                    : p < free   ? 0
                                                                                 : -1;
    }
  return g;
}

}  // namespace adaptive_perception::slam
