#pragma once
// A top-down PNG of a line-landmark map with trajectories over it, for evaluation tools and
// reports: segments in black (anchored/retired ones in blue), trajectories in their colours, a 1 m
// grid, a scale bar, and a legend.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "adaptive_perception/slam/occupancy_grid.h"

namespace adaptive_perception::slam {

struct MapSegment {
  Eigen::Vector2d start_m, end_m;
  bool fixed = false;  // anchored or retired
};

struct MapTrajectory {
  std::string name;
  cv::Scalar bgr;
  std::vector<Eigen::Vector2d> points_m;
};

/// Fits everything into an image of at most max_side_px pixels on its longer side.
cv::Mat drawLineMap(const std::vector<MapSegment>& segments,
                    const std::vector<MapTrajectory>& trajectories, const std::string& title,
                    int max_side_px = 1200);

/// The occupancy grid as map_server's image shows it (occupied black, free white, unknown grey;
/// north up), one pixel per cell.
cv::Mat drawOccupancyGrid(const OccupancyGrid& grid);

}  // namespace adaptive_perception::slam
