#include "adaptive_perception/localization/centre_circle.h"

#include <algorithm>
#include <bitset>
#include <cmath>
#include <stdexcept>

#include "adaptive_perception/math/angles.h"

namespace adaptive_perception::localization {

const config::Fields<CentreCircleConfig>& CentreCircleConfig::fields() {
  using C = CentreCircleConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("circle_max_range_m", &C::max_range_m, config::aboveZero(100),
               "line pixels farther than this on the ground are not used to find the centre "
               "circle (m)")
          .add("circle_inlier_tolerance_m", &C::inlier_tolerance_m, config::aboveZero(1),
               "a line point fits the centre circle or the halfway line within this (m)")
          .add("circle_min_halfway_length_m", &C::min_halfway_length_m, config::aboveZero(100),
               "the halfway line through the circle's centre must be seen this long (m)")
          .add("circle_min_arc_over_line", &C::min_arc_over_line, config::closed(1, 10),
               "the centre circle's points must cover this many times the arc a straight line "
               "fits")
          .add("circle_max_arc_gap_rad", &C::max_arc_gap_rad, config::closed(0, 2 * M_PI),
               "gaps in the centre circle's arc up to this wide are bridged (rad)")
          .add("circle_min_painted_share", &C::min_painted_share, config::closed(0, 1),
               "share of the centre circle in view that must be line paint")
          .add("circle_min_line_width_px", &C::min_line_width_px, config::closed(0, 100),
               "the centre circle's paint is looked for only where it is at least this wide in the "
               "image (px)")
          .add("circle_pixel_stride", &C::pixel_stride, config::closed(1, 64),
               "every this many pixels of a 640-wide image is looked at for the centre circle")
          .add("circle_iterations", &C::iterations, config::closed(1, 100000),
               "RANSAC draws for the centre circle")
          .add("circle_position_sd_m", &C::position_sd_m, config::closed(0, 10),
               "spread of the poses drawn around a centre circle sighting (m)")
          .add("circle_heading_sd_rad", &C::heading_sd_rad, config::closed(0, 3.2),
               "spread of the headings drawn around a centre circle sighting with its halfway "
               "line (rad)");
  return f;
}

namespace {

/// The line pixels on the ground (base_link), within max_range_m. A column's run of white that does
/// not have carpet right above it stands up from the ground (a goal post; a landmark's white base,
/// unless a green band sits on it) or is cut by the image, so none of its pixels is taken for
/// paint.
std::vector<Eigen::Vector2d> groundLinePoints(const cv::Mat& labels,
                                              const world::PinholeCamera& camera,
                                              const Eigen::Isometry3d& base_to_optical,
                                              const CentreCircleConfig& config) {
  std::vector<Eigen::Vector2d> points;
  const Eigen::Vector3d o = base_to_optical.translation();
  if (o.z() <= 0.0) return points;
  const int stride = std::max(1, config.pixel_stride * labels.cols / 640);
  for (int u = stride / 2; u < labels.cols; u += stride) {
    for (int v = 0; v < labels.rows;) {
      if (labels.at<std::uint8_t>(v, u) != world::kWhite) {
        ++v;
        continue;
      }
      int end = v;
      while (end < labels.rows && labels.at<std::uint8_t>(end, u) == world::kWhite) ++end;
      // Paint lies on the carpet: carpet right above the run. A run under anything else stands up
      // from the ground (a goal post, a robot, a landmark's white base under a band that is not
      // green) or reaches the horizon.
      const bool stands = v == 0 || labels.at<std::uint8_t>(v - 1, u) != world::kGreen ||
                          (base_to_optical.linear() * camera.rayThrough(u, v)).z() > -1e-6;
      for (int r = v; r < end && !stands; ++r) {
        if (r % stride != stride / 2) continue;
        const Eigen::Vector3d ray = base_to_optical.linear() * camera.rayThrough(u, r);
        if (ray.z() > -1e-6) continue;
        const Eigen::Vector3d p = o + (-o.z() / ray.z()) * ray;
        if ((p.head<2>() - o.head<2>()).norm() <= config.max_range_m) points.push_back(p.head<2>());
      }
      v = end;
    }
  }
  return points;
}

std::vector<Eigen::Vector2d> inliersOf(const std::vector<Eigen::Vector2d>& points,
                                       const Eigen::Vector2d& centre, double radius, double tol) {
  std::vector<Eigen::Vector2d> in;
  for (const Eigen::Vector2d& p : points)
    if (std::abs((p - centre).norm() - radius) <= tol) in.push_back(p);
  return in;
}

constexpr int kArcBins = 180;  // two degrees each
using ArcBins = std::bitset<kArcBins>;

int arcBin(const Eigen::Vector2d& d) {
  const int k = static_cast<int>((std::atan2(d.y(), d.x()) + M_PI) / (2.0 * M_PI) * kArcBins);
  return std::clamp(k, 0, kArcBins - 1);
}

/// The longest run of set bins around the circle, gaps of up to `max_gap` bins bridged (radians).
double longestArc(const ArcBins& bins, int max_gap) {
  if (bins.none()) return 0.0;
  if (bins.all()) return 2.0 * M_PI;
  // Start just after an empty bin, so that no run wraps past the start.
  int start = 0;
  while (bins.test(start)) ++start;
  int best = 0, run = 0, gap = 0;
  for (int i = 1; i <= kArcBins; ++i) {
    const int k = (start + i) % kArcBins;
    if (bins.test(k)) {
      run += (run > 0 ? gap : 0) + 1;
      gap = 0;
      best = std::max(best, run);
    } else if (++gap > max_gap) {
      run = 0;
      gap = 0;
    }
  }
  return std::min(best, kArcBins) * 2.0 * M_PI / kArcBins;
}

/// The circle's two-degree bins in view (their middle point in the image, within max_range_m,
/// its paint at least min_line_width_px across), and those of them whose pixel, or one next to
/// it, is line paint.
struct CircleView {
  ArcBins in_view, painted;
};
CircleView viewOf(const cv::Mat& labels, const world::PinholeCamera& camera,
                  const Eigen::Isometry3d& base_to_optical, const Eigen::Vector2d& centre,
                  double radius, double line_width_m, const CentreCircleConfig& config) {
  const Eigen::Isometry3d optical_from_base = base_to_optical.inverse();
  const Eigen::Vector2d o = base_to_optical.translation().head<2>();
  const auto pixel = [&](const Eigen::Vector2d& g, Eigen::Vector2d* out) {
    return camera.project(optical_from_base * Eigen::Vector3d(g.x(), g.y(), 0.0), out);
  };
  CircleView view;
  for (int k = 0; k < kArcBins; ++k) {
    const double a = -M_PI + (k + 0.5) * 2.0 * M_PI / kArcBins;
    const Eigen::Vector2d radial(std::cos(a), std::sin(a));
    const Eigen::Vector2d q = centre + radius * radial;
    if ((q - o).norm() > config.max_range_m) continue;
    Eigen::Vector2d uv, inner, outer;
    if (!pixel(q, &uv) || !pixel(q - 0.5 * line_width_m * radial, &inner) ||
        !pixel(q + 0.5 * line_width_m * radial, &outer))
      continue;
    // Paint thinner than min_line_width_px in the image is beyond what the segmentation resolves.
    if ((outer - inner).norm() < config.min_line_width_px) continue;
    // project() puts pixel u's centre at u + 0.5 (rayThrough's convention).
    const int u = static_cast<int>(std::floor(uv.x())), v = static_cast<int>(std::floor(uv.y()));
    if (u < 1 || v < 1 || u >= labels.cols - 1 || v >= labels.rows - 1) continue;
    view.in_view.set(k);
    bool paint = false;
    for (int dv = -1; dv <= 1 && !paint; ++dv)
      for (int du = -1; du <= 1 && !paint; ++du)
        paint = labels.at<std::uint8_t>(v + dv, u + du) == world::kWhite;
    view.painted.set(k, paint);
  }
  return view;
}

/// The arc a circle's inliers must cover: min_arc_over_line times the arc a straight line fits
/// within `tol` of a circle of `radius` (see the header).
double minArcRad(double radius, double tol, const CentreCircleConfig& config) {
  return config.min_arc_over_line * 4.0 * std::sqrt(tol / radius);
}

}  // namespace

bool centreCircleFindable(const world::FieldMap& map, const CentreCircleConfig& config) {
  const double radius = 0.5 * map.dimensions().centre_circle_diameter_m;
  return radius > 0.0 && minArcRad(radius, config.inlier_tolerance_m, config) <= M_PI;
}

std::optional<CentreCircleSighting> detectCentreCircle(const color::FieldSegmentation& seg,
                                                       const world::PinholeCamera& camera,
                                                       const Eigen::Isometry3d& base_to_optical,
                                                       const world::FieldMap& map,
                                                       const CentreCircleConfig& config,
                                                       std::uint64_t seed) {
  const double radius = 0.5 * map.dimensions().centre_circle_diameter_m;
  const double tol = config.inlier_tolerance_m;
  if (seg.labels.type() != CV_8UC1 || seg.labels.cols != camera.width_px ||
      seg.labels.rows != camera.height_px)
    throw std::invalid_argument(
        "detectCentreCircle: needs the segmentation's labels (CV_8UC1) of "
        "the camera's size");
  if (!centreCircleFindable(map, config)) return std::nullopt;
  const double min_arc_rad = minArcRad(radius, tol, config);
  const std::vector<Eigen::Vector2d> points =
      groundLinePoints(seg.labels, camera, base_to_optical, config);
  if (points.size() < 3) return std::nullopt;
  // RANSAC: two points on the circle put its centre at one of two places. A candidate scores the
  // arc its inliers cover (two-degree bins with an inlier), not their count (the carpet near the
  // camera holds far more pixels per metre, and a circle through a stretch of thick near line
  // would outnumber the true circle's far arc), less the arc in view that holds none (a circle
  // through fragments of several lines covers a wide arc, and misses more).
  const double line_width_m = map.dimensions().line_width_m;
  const int min_bins = static_cast<int>(std::ceil(min_arc_rad / (2.0 * M_PI) * kArcBins));
  math::Rng rng(seed);
  std::optional<Eigen::Vector2d> best;
  int best_score = 0;
  const int n = static_cast<int>(points.size());
  for (int it = 0; it < config.iterations; ++it) {
    const Eigen::Vector2d a = points[rng.uniformInt(0, n - 1)],
                          b = points[rng.uniformInt(0, n - 1)];
    const Eigen::Vector2d mid = 0.5 * (a + b), ab = b - a;
    const double half = 0.5 * ab.norm();
    if (half < 2.0 * tol || half >= radius) continue;
    const Eigen::Vector2d normal = Eigen::Vector2d(-ab.y(), ab.x()).normalized();
    const double h = std::sqrt(radius * radius - half * half);
    for (double side : {-1.0, 1.0}) {
      const Eigen::Vector2d c = mid + side * h * normal;
      ArcBins covered;
      for (const Eigen::Vector2d& p : points)
        if (std::abs((p - c).norm() - radius) <= tol) covered.set(arcBin(p - c));
      const int count = static_cast<int>(covered.count());
      if (count < min_bins || count <= best_score) continue;
      const CircleView view =
          viewOf(seg.labels, camera, base_to_optical, c, radius, line_width_m, config);
      const int score = count - static_cast<int>((view.in_view & ~covered).count());
      if (score > best_score) best_score = score, best = c;
    }
  }
  if (!best) return std::nullopt;
  // Least squares on the inliers (Gauss-Newton on the centre, the radius known).
  Eigen::Vector2d c = *best;
  for (int iter = 0; iter < 5; ++iter) {
    const std::vector<Eigen::Vector2d> in = inliersOf(points, c, radius, tol);
    if (in.size() < 3) return std::nullopt;
    Eigen::Matrix2d jtj = Eigen::Matrix2d::Zero();
    Eigen::Vector2d jtr = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& p : in) {
      const Eigen::Vector2d d = c - p;
      const double dist = d.norm();
      if (dist < 1e-9) continue;
      const Eigen::Vector2d j = d / dist;  // d(dist - R) / dc
      jtj += j * j.transpose();
      jtr += j * (dist - radius);
    }
    if (std::abs(jtj.determinant()) < 1e-12) break;
    c -= jtj.ldlt().solve(jtr);
  }
  const std::vector<Eigen::Vector2d> in = inliersOf(points, c, radius, tol);
  CentreCircleSighting s;
  s.centre_m = c;
  s.inliers = static_cast<int>(in.size());
  ArcBins covered;
  for (const Eigen::Vector2d& p : in) covered.set(arcBin(p - c));
  // One arc: two straight lines through a circle that is not there (a corner of the field, a line
  // meeting the touch line) fill two short arcs, each at most a line's; the circle's paint is one
  // long arc, broken only where something stands on it.
  s.arc_rad = longestArc(
      covered, static_cast<int>(std::floor(config.max_arc_gap_rad / (2.0 * M_PI) * kArcBins)));
  if (s.arc_rad < min_arc_rad) return std::nullopt;
  // Line fragments can fill a wide arc of a circle that is not there (a circle through two lines'
  // corner); the circle's own paint must then be missing along much of it. Where the circle lies
  // in view (in the image, within range), it must be paint.
  const CircleView view =
      viewOf(seg.labels, camera, base_to_optical, c, radius, line_width_m, config);
  const double painted_arc_rad = static_cast<double>(view.painted.count()) / kArcBins * 2.0 * M_PI;
  s.painted_share = view.in_view.any() ? static_cast<double>(view.painted.count()) /
                                             static_cast<double>(view.in_view.count())
                                       : 0.0;
  if (s.painted_share < config.min_painted_share || painted_arc_rad < min_arc_rad)
    return std::nullopt;
  // The halfway line: the direction through the centre that the most other line points lie on
  // (a half-degree histogram of their directions modulo pi, each point within the tolerance of
  // the line voting for the directions it fits).
  std::vector<Eigen::Vector2d> rest;
  for (const Eigen::Vector2d& p : points)
    if (std::abs((p - c).norm() - radius) > tol) rest.push_back(p);
  constexpr int kBins = 360;
  std::vector<std::vector<double>> along(kBins);
  for (const Eigen::Vector2d& p : rest) {
    const Eigen::Vector2d d = p - c;
    const double r = d.norm();
    if (r < 2.0 * tol) continue;  // near the centre a point fits every direction
    const double dir = std::atan2(d.y(), d.x());
    // The directions theta with |r sin(dir - theta)| <= tol.
    const double spread = std::asin(std::min(1.0, tol / r));
    const int b0 = static_cast<int>(std::floor((dir - spread) / M_PI * kBins)),
              b1 = static_cast<int>(std::floor((dir + spread) / M_PI * kBins));
    for (int b = b0; b <= b1; ++b) {
      const int k = ((b % kBins) + kBins) % kBins;
      // Signed position along the direction k (the sign flips with each half turn).
      const double theta = (k + 0.5) * M_PI / kBins;
      along[k].push_back(d.x() * std::cos(theta) + d.y() * std::sin(theta));
    }
  }
  double best_length = 0.0;
  for (int k = 0; k < kBins; ++k) {
    if (along[k].size() < 3) continue;
    const auto [lo, hi] = std::minmax_element(along[k].begin(), along[k].end());
    // The extent, counting only as much of it as the points fill (a few scattered points far
    // apart are not a line): points per tolerance-long piece.
    const double extent = *hi - *lo;
    const double filled = std::min(extent, along[k].size() * tol);
    if (filled > best_length) {
      best_length = filled;
      s.halfway_direction_rad = (k + 0.5) * M_PI / kBins;
    }
  }
  if (best_length < config.min_halfway_length_m) s.halfway_direction_rad.reset();
  return s;
}

std::vector<math::SE2> centreCirclePoses(const CentreCircleSighting& s, const world::FieldMap& map,
                                         const CentreCircleConfig& config, int count,
                                         math::Rng& rng) {
  std::vector<math::SE2> poses;
  // The robot at p with heading psi sees the centre (the map's origin) at c: p = -R(psi) c. The
  // halfway line runs along the map's y axis: psi + direction = pi / 2 (modulo pi).
  for (int k = 0; k < count / 2; ++k) {
    const double psi =
        s.halfway_direction_rad
            ? 0.5 * M_PI - *s.halfway_direction_rad + rng.gaussian(0.0, config.heading_sd_rad)
            : 2.0 * M_PI * (k + rng.uniform()) / std::max(1, count / 2);
    const Eigen::Vector2d c = s.centre_m + Eigen::Vector2d(rng.gaussian(0.0, config.position_sd_m),
                                                           rng.gaussian(0.0, config.position_sd_m));
    const Eigen::Vector2d p = -(Eigen::Rotation2Dd(psi).toRotationMatrix() * c);
    const math::SE2 pose(p.x(), p.y(), math::wrapAngle(psi));
    if (std::abs(p.x()) > map.carpetHalfLength() || std::abs(p.y()) > map.carpetHalfWidth())
      continue;
    poses.push_back(pose);
    poses.push_back(math::pointMirror(pose));
  }
  return poses;
}

}  // namespace adaptive_perception::localization
