#include "adaptive_perception/slam/map_drawing.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace adaptive_perception::slam {

cv::Mat drawLineMap(const std::vector<MapSegment>& segments,
                    const std::vector<MapTrajectory>& trajectories, const std::string& title,
                    int max_side_px) {
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  auto grow = [&](const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  for (const auto& s : segments) {
    grow(s.start_m);
    grow(s.end_m);
  }
  for (const auto& t : trajectories)
    for (const auto& p : t.points_m) grow(p);
  if (lo.x() > hi.x()) lo = hi = Eigen::Vector2d::Zero();
  lo -= Eigen::Vector2d(1.0, 1.0);
  hi += Eigen::Vector2d(1.0, 1.0);
  const double span = std::max(hi.x() - lo.x(), hi.y() - lo.y());
  const double scale = (max_side_px - 40) / span;  // px per m
  const int w = static_cast<int>((hi.x() - lo.x()) * scale) + 40;
  const int h = static_cast<int>((hi.y() - lo.y()) * scale) + 80;
  cv::Mat img(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
  auto px = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(20 + (p.x() - lo.x()) * scale),
                     static_cast<int>(h - 20 - (p.y() - lo.y()) * scale));
  };
  for (double x = std::ceil(lo.x()); x <= hi.x(); x += 1.0)
    cv::line(img, px({x, lo.y()}), px({x, hi.y()}), cv::Scalar(235, 235, 235), 1);
  for (double y = std::ceil(lo.y()); y <= hi.y(); y += 1.0)
    cv::line(img, px({lo.x(), y}), px({hi.x(), y}), cv::Scalar(235, 235, 235), 1);
  for (const auto& t : trajectories)
    for (size_t i = 1; i < t.points_m.size(); ++i)
      cv::line(img, px(t.points_m[i - 1]), px(t.points_m[i]), t.bgr, 1, cv::LINE_AA);
  for (const auto& s : segments)
    cv::line(img, px(s.start_m), px(s.end_m),
             s.fixed ? cv::Scalar(200, 80, 0) : cv::Scalar(0, 0, 0), 2, cv::LINE_AA);
  cv::putText(img, title, cv::Point(10, 22), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  int y = 44;
  for (const auto& t : trajectories) {
    cv::line(img, cv::Point(10, y - 4), cv::Point(30, y - 4), t.bgr, 2);
    cv::putText(img, t.name, cv::Point(36, y), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0),
                1, cv::LINE_AA);
    y += 18;
  }
  const int bar = static_cast<int>(std::round(5.0 * scale));
  cv::line(img, cv::Point(w - 20 - bar, h - 8), cv::Point(w - 20, h - 8), cv::Scalar(0, 0, 0), 2);
  cv::putText(img, "5 m", cv::Point(w - 20 - bar, h - 12), cv::FONT_HERSHEY_SIMPLEX, 0.4,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  return img;
}

cv::Mat drawOccupancyGrid(const OccupancyGrid& grid) {
  cv::Mat img(grid.height, grid.width, CV_8UC1);
  for (int y = 0; y < grid.height; ++y)
    for (int x = 0; x < grid.width; ++x) {
      const std::int8_t v = grid.at(x, y);
      img.at<uchar>(grid.height - 1 - y, x) = v < 0 ? 205 : v >= 50 ? 0 : 254;
    }
  return img;
}

}  // namespace adaptive_perception::slam
