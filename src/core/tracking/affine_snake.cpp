#include "adaptive_perception/tracking/affine_snake.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace adaptive_perception::tracking {

Contour resampleContour(const std::vector<cv::Point>& polygon, int n) {
  if (polygon.size() < 3) throw std::invalid_argument("resampleContour: fewer than 3 vertices");
  if (n < 3) throw std::invalid_argument("resampleContour: fewer than 3 points asked");
  std::vector<double> cum(polygon.size() + 1, 0.0);
  for (size_t i = 0; i < polygon.size(); ++i) {
    const cv::Point d = polygon[(i + 1) % polygon.size()] - polygon[i];
    cum[i + 1] = cum[i] + std::hypot(d.x, d.y);
  }
  const double total = cum.back();
  if (total <= 0.0) throw std::invalid_argument("resampleContour: polygon of zero length");
  Contour out;
  out.reserve(n);
  size_t seg = 0;
  for (int k = 0; k < n; ++k) {
    const double s = total * k / n;
    while (seg + 1 < polygon.size() && cum[seg + 1] <= s) ++seg;
    const double len = cum[seg + 1] - cum[seg];
    const double u = len > 0.0 ? (s - cum[seg]) / len : 0.0;
    const cv::Point a = polygon[seg], b = polygon[(seg + 1) % polygon.size()];
    out.emplace_back(a.x + u * (b.x - a.x), a.y + u * (b.y - a.y));
  }
  return out;
}

Contour ellipseContour(double cx, double cy, double ax, double ay, int n) {
  Contour c;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * M_PI * k / n;
    c.emplace_back(cx + ax * std::cos(t), cy + ay * std::sin(t));
  }
  return c;
}

double contourArea(const Contour& c) {
  double a = 0.0;
  for (size_t i = 0; i < c.size(); ++i) {
    const auto& p = c[i];
    const auto& q = c[(i + 1) % c.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return std::abs(a) / 2.0;
}

Eigen::Vector2d contourCentroid(const Contour& c) {
  Eigen::Vector2d m = Eigen::Vector2d::Zero();
  for (const auto& p : c) m += p;
  return c.empty() ? m : Eigen::Vector2d(m / static_cast<double>(c.size()));
}

cv::Rect2d contourBox(const Contour& c) {
  if (c.empty()) return {};
  double x0 = c[0].x(), x1 = x0, y0 = c[0].y(), y1 = y0;
  for (const auto& p : c) {
    x0 = std::min(x0, p.x());
    x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y());
    y1 = std::max(y1, p.y());
  }
  return {x0, y0, x1 - x0, y1 - y0};
}

Contour applyAffine(const Affine2& t, const Contour& c) {
  Contour out;
  out.reserve(c.size());
  for (const auto& p : c) out.push_back(t.leftCols<2>() * p + t.col(2));
  return out;
}

cv::Mat contourMask(const Contour& c, cv::Size size, cv::Point offset) {
  cv::Mat mask = cv::Mat::zeros(size, CV_8U);
  if (c.size() < 3) return mask;
  std::vector<cv::Point> pts;
  pts.reserve(c.size());
  for (const auto& p : c)
    pts.emplace_back(static_cast<int>(std::lround(p.x())) - offset.x,
                     static_cast<int>(std::lround(p.y())) - offset.y);
  cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{pts}, cv::Scalar(255));
  return mask;
}

void AffineSnakeConfig::validate() const {
  if (iterations < 1 || iterations > 1000)
    throw std::invalid_argument("iterations must be in 1..1000");
  if (search_px < 1 || search_px > 500) throw std::invalid_argument("search_px must be in 1..500");
  if (!(damping >= 0.0)) throw std::invalid_argument("damping must be >= 0");
  if (!(converged_px > 0.0)) throw std::invalid_argument("converged_px must be > 0");
  if (!(on_edge_px >= 0.0)) throw std::invalid_argument("on_edge_px must be >= 0");
}

namespace {
inline bool edgeAt(const cv::Mat& edges, int x, int y) {
  return x >= 0 && y >= 0 && x < edges.cols && y < edges.rows && edges.at<uchar>(y, x) != 0;
}
}  // namespace

double onEdgeShare(const Contour& c, const cv::Mat& edges, cv::Point offset, double radius_px) {
  if (c.empty()) return 0.0;
  const int r = static_cast<int>(std::ceil(radius_px));
  int on = 0;
  for (const auto& p : c) {
    const int x = static_cast<int>(std::lround(p.x())) - offset.x;
    const int y = static_cast<int>(std::lround(p.y())) - offset.y;
    bool hit = false;
    for (int dy = -r; dy <= r && !hit; ++dy)
      for (int dx = -r; dx <= r && !hit; ++dx)
        if (dx * dx + dy * dy <= radius_px * radius_px + 1e-9) hit = edgeAt(edges, x + dx, y + dy);
    on += hit;
  }
  return static_cast<double>(on) / c.size();
}

AffineSnakeFit fitAffineSnake(const Contour& start, const cv::Mat& edges, cv::Point offset,
                              const AffineSnakeConfig& config) {
  config.validate();
  if (edges.type() != CV_8U) throw std::invalid_argument("fitAffineSnake: edges must be CV_8U");
  AffineSnakeFit fit;
  fit.contour = start;
  const int n = static_cast<int>(start.size());
  if (n < 3) throw std::invalid_argument("fitAffineSnake: contour of fewer than 3 points");
  // Least squares in coordinates centred on the start contour, damped per parameter
  // (Levenberg-Marquardt style), so translation and the linear part are damped alike.
  const Eigen::Vector2d c0 = contourCentroid(start);
  for (int it = 0; it < config.iterations; ++it) {
    // Matches along the normals of the current contour.
    Eigen::Matrix<double, 3, 3> xtx = Eigen::Matrix3d::Zero();
    Eigen::Matrix<double, 3, 2> xty = Eigen::Matrix<double, 3, 2>::Zero();
    int matched = 0;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d& c = fit.contour[i];
      const Eigen::Vector2d tangent = fit.contour[(i + 1) % n] - fit.contour[(i + n - 1) % n];
      const double tl = tangent.norm();
      if (tl <= 1e-9) continue;
      const Eigen::Vector2d normal(-tangent.y() / tl, tangent.x() / tl);
      const double cx = c.x() - offset.x, cy = c.y() - offset.y;
      bool found = false;
      Eigen::Vector2d q;
      for (int t = 0; t <= config.search_px && !found; ++t) {
        for (int sgn : {1, -1}) {
          if (t == 0 && sgn < 0) continue;
          const double x = cx + sgn * t * normal.x(), y = cy + sgn * t * normal.y();
          if (edgeAt(edges, static_cast<int>(std::lround(x)), static_cast<int>(std::lround(y)))) {
            q = Eigen::Vector2d(x + offset.x, y + offset.y);
            found = true;
            break;
          }
        }
      }
      if (!found) continue;
      ++matched;
      const Eigen::Vector3d p(start[i].x() - c0.x(), start[i].y() - c0.y(), 1.0);
      xtx += p * p.transpose();
      xty += p * q.transpose();
    }
    fit.matched = matched;
    fit.iterations = it + 1;
    if (matched < 6) break;
    // Damped towards the current transform: (X'X + l D) T' = X'Q + l D T_cur', D = diag(X'X).
    Affine2 cur_c = fit.transform;  // in centred coordinates: t' = t + A c0
    cur_c.col(2) += fit.transform.leftCols<2>() * c0;
    const Eigen::Matrix3d damp = config.damping * Eigen::Matrix3d(xtx.diagonal().asDiagonal());
    const Eigen::Matrix<double, 3, 2> sol =
        (xtx + damp).ldlt().solve(xty + damp * cur_c.transpose());
    if (!sol.allFinite()) break;
    Affine2 next = sol.transpose();
    next.col(2) -= next.leftCols<2>() * c0;
    const Contour moved = applyAffine(next, start);
    double max_move = 0.0;
    for (int i = 0; i < n; ++i) max_move = std::max(max_move, (moved[i] - fit.contour[i]).norm());
    fit.transform = next;
    fit.contour = moved;
    if (max_move < config.converged_px) break;
  }
  fit.on_edge = onEdgeShare(fit.contour, edges, offset, config.on_edge_px);
  return fit;
}

int eulerNumber(const cv::Mat& binary) {
  if (binary.type() != CV_8U) throw std::invalid_argument("eulerNumber: binary must be CV_8U");
  long q1 = 0, q3 = 0, qd = 0;
  // Quads over the image padded by one background pixel on every side.
  auto px = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < binary.cols && y < binary.rows && binary.at<uchar>(y, x) != 0;
  };
  for (int y = -1; y < binary.rows; ++y)
    for (int x = -1; x < binary.cols; ++x) {
      const bool a = px(x, y), b = px(x + 1, y), c = px(x, y + 1), d = px(x + 1, y + 1);
      const int s = a + b + c + d;
      if (s == 1)
        ++q1;
      else if (s == 3)
        ++q3;
      else if (s == 2 && a == d)
        ++qd;  // the two set pixels are diagonal
    }
  return static_cast<int>((q1 - q3 - 2 * qd) / 4);
}

}  // namespace adaptive_perception::tracking
