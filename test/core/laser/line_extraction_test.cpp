#include "adaptive_perception/laser/line_extraction.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "../refusal.h"
#include "adaptive_perception/math/rng.h"

using namespace adaptive_perception;
using namespace adaptive_perception::laser;

namespace {
std::vector<Eigen::Vector2d> polyline(const std::vector<Eigen::Vector2d>& corners, int per_edge) {
  std::vector<Eigen::Vector2d> pts;
  for (size_t c = 0; c + 1 < corners.size(); ++c)
    for (int k = 0; k < per_edge; ++k)
      pts.push_back(corners[c] + (corners[c + 1] - corners[c]) * (double(k) / per_edge));
  pts.push_back(corners.back());
  return pts;
}

// A scan of a rectangular room from inside: ranges to the nearest wall along each bearing.
LaserScan2D roomScan(double x0, double x1, double y0, double y1, int beams, double fov,
                     double noise, math::Rng* rng) {
  LaserScan2D s;
  s.angle_min_rad = -fov / 2;
  s.angle_increment_rad = fov / (beams - 1);
  s.range_min_m = 0.02;
  s.range_max_m = 30.0;
  for (int i = 0; i < beams; ++i) {
    const double b = s.bearing(i), c = std::cos(b), sn = std::sin(b);
    double t = std::numeric_limits<double>::infinity();
    if (c > 1e-12) t = std::min(t, x1 / c);
    if (c < -1e-12) t = std::min(t, x0 / c);
    if (sn > 1e-12) t = std::min(t, y1 / sn);
    if (sn < -1e-12) t = std::min(t, y0 / sn);
    s.ranges_m.push_back(static_cast<float>(t + (rng ? rng->gaussian(0.0, noise) : 0.0)));
  }
  return s;
}
}  // namespace

TEST(PolylineSplit, SplitsExactlyAtCorners) {
  const auto pts = polyline({{0, 0}, {2, 0}, {2, 1.5}, {0.5, 3}, {0.5, 4}}, 20);
  for (auto method : {SplitMethod::kRecursive, SplitMethod::kHullTree}) {
    const std::vector<int> v = simplifyPolyline(pts, 0.01, method);
    EXPECT_EQ(v, (std::vector<int>{0, 20, 40, 60, 80}));
  }
  // A straight run is one piece.
  const auto line = polyline({{0, 0}, {5, 1}}, 50);
  EXPECT_EQ(simplifyPolyline(line, 0.01, SplitMethod::kRecursive), (std::vector<int>{0, 50}));
}

TEST(PolylineSplit, FarthestPointByHand) {
  const std::vector<Eigen::Vector2d> p = {{0, 0}, {1, 0.5}, {2, -2}, {3, 1}, {4, 0}};
  const FarthestPoint f = findFarthestLinear(p, 0, 4);
  EXPECT_EQ(f.index, 2);
  EXPECT_NEAR(f.distance_m, 2.0, 1e-12);
  const HullTree tree(p);
  const FarthestPoint g = tree.findFarthest(0, 4);
  EXPECT_EQ(g.index, 2);
  EXPECT_NEAR(g.distance_m, 2.0, 1e-12);
  EXPECT_EQ(tree.findFarthest(1, 3).index, 2);
  EXPECT_EQ(tree.findFarthest(2, 3).index, -1);
}

// Both implementations give identical output on random inputs (noisy walks, random clouds).
TEST(PolylineSplit, HullTreeAgreesWithRecursiveOnRandomInputs) {
  math::Rng rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = rng.uniformInt(2, 400);
    std::vector<Eigen::Vector2d> pts;
    Eigen::Vector2d p(0, 0), heading(1, 0);
    for (int k = 0; k < n; ++k) {
      if (trial % 3 == 0) {
        pts.push_back({rng.uniform(-5, 5), rng.uniform(-5, 5)});
      } else {
        const double turn = rng.bernoulli(0.05) ? rng.uniform(-2, 2) : 0.0;
        heading = Eigen::Rotation2Dd(turn) * heading;
        p += 0.05 * heading + Eigen::Vector2d{rng.gaussian(0, 0.005), rng.gaussian(0, 0.005)};
        pts.push_back(p);
      }
    }
    const double eps = rng.uniform(0.001, 0.3);
    EXPECT_EQ(simplifyPolyline(pts, eps, SplitMethod::kRecursive),
              simplifyPolyline(pts, eps, SplitMethod::kHullTree))
        << "trial " << trial << " n " << n << " eps " << eps;
    const HullTree tree(pts);
    for (int q = 0; q < 20 && n > 2; ++q) {
      int i = rng.uniformInt(0, n - 1), j = rng.uniformInt(0, n - 1);
      if (i > j) std::swap(i, j);
      const FarthestPoint a = findFarthestLinear(pts, i, j), b = tree.findFarthest(i, j);
      EXPECT_EQ(a.index, b.index);
      EXPECT_NEAR(a.distance_m, b.distance_m, 1e-9);
    }
  }
}

TEST(LineFit, ExactLineAndHandComputedParameters) {
  // Points on x = 2 (a wall ahead): rho 2, alpha 0.
  std::vector<Eigen::Vector2d> p;
  for (int k = -5; k <= 5; ++k) p.emplace_back(2.0, 0.1 * k);
  PolarLine l = fitLine(p, 0, static_cast<int>(p.size()) - 1, {});
  EXPECT_NEAR(l.rho_m, 2.0, 1e-12);
  EXPECT_NEAR(l.alpha_rad, 0.0, 1e-12);
  // Points on y = -1 (a wall to the right): rho 1, alpha -pi/2.
  p.clear();
  for (int k = 0; k < 10; ++k) p.emplace_back(0.3 * k, -1.0);
  l = fitLine(p, 0, 9, {});
  EXPECT_NEAR(l.rho_m, 1.0, 1e-12);
  EXPECT_NEAR(l.alpha_rad, -M_PI / 2, 1e-12);
  EXPECT_NEAR(lineDistance(l, {5.0, -1.0}), 0.0, 1e-12);
  EXPECT_NEAR((projectOnLine(l, {2.0, 0.5}) - Eigen::Vector2d(2.0, -1.0)).norm(), 0.0, 1e-12);
}

// The propagated covariance of (rho, alpha) matches a Monte Carlo estimate over noisy scans of a
// wall.
TEST(LineFit, CovarianceMatchesMonteCarlo) {
  const double sr = 0.02, sphi = 0.002;
  std::vector<double> ranges, bearings;
  for (int k = 0; k < 40; ++k) {
    const double b = -0.4 + 0.02 * k;
    bearings.push_back(b);
    // wall x cos(0.3) + y sin(0.3) = 3
    ranges.push_back(3.0 / std::cos(b - 0.3));
  }
  std::vector<Eigen::Vector2d> pts(40);
  std::vector<Eigen::Matrix2d> covs(40);
  for (int k = 0; k < 40; ++k) {
    pts[k] = ranges[k] * Eigen::Vector2d(std::cos(bearings[k]), std::sin(bearings[k]));
    covs[k] = polarPointCovariance(ranges[k], bearings[k], sr, sphi);
  }
  const PolarLine predicted = fitLine(pts, 0, 39, covs);
  EXPECT_NEAR(predicted.rho_m, 3.0, 1e-9);
  EXPECT_NEAR(predicted.alpha_rad, 0.3, 1e-9);
  math::Rng rng(3);
  const int n = 20000;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  Eigen::Matrix2d sum_sq = Eigen::Matrix2d::Zero();
  for (int t = 0; t < n; ++t) {
    for (int k = 0; k < 40; ++k) {
      const double r = ranges[k] + rng.gaussian(0, sr), b = bearings[k] + rng.gaussian(0, sphi);
      pts[k] = r * Eigen::Vector2d(std::cos(b), std::sin(b));
    }
    const PolarLine l = fitLine(pts, 0, 39, {});
    const Eigen::Vector2d x(l.rho_m, l.alpha_rad);
    sum += x;
    sum_sq += x * x.transpose();
  }
  const Eigen::Vector2d mean = sum / n;
  const Eigen::Matrix2d mc = sum_sq / n - mean * mean.transpose();
  EXPECT_NEAR(mc(0, 0) / predicted.cov(0, 0), 1.0, 0.05);
  EXPECT_NEAR(mc(1, 1) / predicted.cov(1, 1), 1.0, 0.05);
  const double corr_mc = mc(0, 1) / std::sqrt(mc(0, 0) * mc(1, 1));
  const double corr_pred =
      predicted.cov(0, 1) / std::sqrt(predicted.cov(0, 0) * predicted.cov(1, 1));
  EXPECT_NEAR(corr_mc, corr_pred, 0.05);
}

TEST(LineExtraction, RoomGivesItsWalls) {
  math::Rng rng(5);
  LineExtractionConfig cfg;
  for (auto method : {SplitMethod::kRecursive, SplitMethod::kHullTree}) {
    cfg.split_method = method;
    LineExtractor ex(cfg);
    const LaserScan2D scan = roomScan(-2.0, 4.0, -1.5, 2.5, 361, 2 * M_PI * 0.75, 0.005, &rng);
    const auto segs = ex.extract(scan);
    // 270-degree scan of a room: the front wall (x = 4), left (y = 2.5), right (y = -1.5) and part
    // of the back wall.
    ASSERT_GE(segs.size(), 3u);
    auto has = [&](double rho, double alpha) {
      for (const auto& s : segs)
        if (std::fabs(s.line.rho_m - rho) < 0.03 &&
            std::fabs(std::remainder(s.line.alpha_rad - alpha, 2 * M_PI)) < 0.02)
          return true;
      return false;
    };
    EXPECT_TRUE(has(4.0, 0.0));
    EXPECT_TRUE(has(2.5, M_PI / 2));
    EXPECT_TRUE(has(1.5, -M_PI / 2));
    for (const auto& s : segs) {
      EXPECT_GE(s.num_points, cfg.min_points);
      EXPECT_GE(s.length(), cfg.min_length_m);
      EXPECT_GT(s.line.cov(0, 0), 0.0);
    }
  }
}

TEST(LineExtraction, DropsInvalidRanges) {
  LaserScan2D s;
  s.angle_min_rad = 0;
  s.angle_increment_rad = 0.01;
  s.range_min_m = 0.1;
  s.range_max_m = 10.0;
  s.ranges_m = {std::numeric_limits<float>::quiet_NaN(),
                std::numeric_limits<float>::infinity(),
                0.05f,
                10.0f,
                12.0f,
                -1.0f,
                3.0f};
  std::vector<ScanPoint> pts;
  EXPECT_EQ(validPoints(s, 0.0, &pts), 6);
  ASSERT_EQ(pts.size(), 1u);
  EXPECT_EQ(pts[0].beam, 6);
  LineExtractor ex;
  EXPECT_TRUE(ex.extract(s).empty());
  LaserScan2D empty;
  EXPECT_TRUE(ex.extract(empty).empty());
}

// A scan whose angle_min is +inf (a hostile or broken driver) has finite ranges at non-finite
// bearings: its geometry is refused by name, and an extractor given it anyway makes no segment
// (the split used to read before the start of its points and published NaN segments).
TEST(LineExtraction, NonFiniteScanGeometryIsNamedAndGivesNoSegments) {
  math::Rng rng(5);
  LaserScan2D scan = roomScan(-2.0, 4.0, -1.5, 2.5, 361, 2 * M_PI * 0.75, 0.005, &rng);
  EXPECT_EQ(scanGeometryProblem(scan), "");
  const auto problem = [&](auto change) {
    LaserScan2D s = scan;
    change(s);
    return scanGeometryProblem(s);
  };
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(problem([&](LaserScan2D& s) { s.angle_min_rad = inf; }), "angle_min inf is not finite");
  EXPECT_NE(problem([&](LaserScan2D& s) { s.angle_increment_rad = 0.0; }).find("angle_increment 0"),
            std::string::npos);
  EXPECT_NE(problem([&](LaserScan2D& s) {
              s.angle_increment_rad = std::nan("");
            }).find("angle_increment"),
            std::string::npos);
  EXPECT_NE(problem([&](LaserScan2D& s) { s.angle_increment_rad = 1e307; }).find("last beam"),
            std::string::npos);
  EXPECT_NE(problem([&](LaserScan2D& s) { s.range_max_m = 0.0; }).find("range_max 0"),
            std::string::npos);
  EXPECT_NE(problem([&](LaserScan2D& s) { s.range_min_m = std::nan(""); }).find("range_min"),
            std::string::npos);
  EXPECT_EQ(problem([&](LaserScan2D& s) { s.range_max_m = inf; }), "");  // no limit
  for (auto method : {SplitMethod::kRecursive, SplitMethod::kHullTree}) {
    LineExtractionConfig cfg;
    cfg.split_method = method;
    LineExtractor ex(cfg);
    LaserScan2D s = scan;
    s.angle_min_rad = inf;
    std::vector<ScanPoint> pts;
    EXPECT_EQ(validPoints(s, 0.0, &pts), static_cast<int>(s.ranges_m.size()));
    EXPECT_TRUE(ex.extract(s).empty());
  }
}

TEST(LineExtraction, RejectsBadConfigByName) {
  LineExtractionConfig c;
  c.split_threshold_m = 0.0;
  EXPECT_TRUE(test_support::refusedNaming([&] { c.validate(); }, "split_threshold_m"));
  EXPECT_THROW(parseSplitMethod("magic"), std::invalid_argument);
}
