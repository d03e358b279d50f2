#include "adaptive_perception/slam/scan_matcher.h"

#include <algorithm>
#include <cmath>
#include <Eigen/Eigenvalues>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "adaptive_perception/math/angles.h"

namespace adaptive_perception::slam {

namespace {
// The likelihood field is cut at this many hit_std from the nearest map point (exp(-8) = 3e-4).
constexpr double kFieldRadiusStd = 4.0;

void need(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}
}  // namespace

void ScanMatcherConfig::validate() const {
  need(std::isfinite(resolution_m) && resolution_m >= 0.005 && resolution_m <= 1.0,
       "ScanMatcherConfig: resolution_m must be in [0.005, 1]");
  need(std::isfinite(hit_std_m) && hit_std_m > 0.0 && hit_std_m <= 5.0,
       "ScanMatcherConfig: hit_std_m must be in (0, 5]");
  need(std::isfinite(search_xy_m) && search_xy_m >= 0.0 && search_xy_m <= 50.0 * resolution_m,
       "ScanMatcherConfig: search_xy_m must be in [0, 50 resolution_m]");
  need(std::isfinite(search_yaw_rad) && search_yaw_rad >= 0.0 && search_yaw_rad <= 3.2,
       "ScanMatcherConfig: search_yaw_rad must be in [0, 3.2]");
  need(std::isfinite(yaw_step_rad) && yaw_step_rad >= 1e-4 && yaw_step_rad <= 0.5,
       "ScanMatcherConfig: yaw_step_rad must be in [1e-4, 0.5]");
  need(std::isfinite(prior_penalty) && prior_penalty >= 0.0 && prior_penalty <= 1.0,
       "ScanMatcherConfig: prior_penalty must be in [0, 1]");
}

void LaserOdometryConfig::validate() const {
  matcher.validate();
  need(std::isfinite(max_range_m) && max_range_m > 0.1,
       "LaserOdometryConfig: max_range_m must be > 0.1");
  need(std::isfinite(keyframe_translation_m) && keyframe_translation_m >= 0.0,
       "LaserOdometryConfig: keyframe_translation_m must be >= 0");
  need(std::isfinite(keyframe_rotation_rad) && keyframe_rotation_rad >= 0.0,
       "LaserOdometryConfig: keyframe_rotation_rad must be >= 0");
  need(local_map_keyframes >= 1 && local_map_keyframes <= 10000,
       "LaserOdometryConfig: local_map_keyframes must be in [1, 10000]");
  need(std::isfinite(min_score) && min_score >= 0.0 && min_score <= 1.0,
       "LaserOdometryConfig: min_score must be in [0, 1]");
  need(min_points >= 1, "LaserOdometryConfig: min_points must be >= 1");
  need(std::isfinite(edge_margin_m) && edge_margin_m >= 0.0,
       "LaserOdometryConfig: edge_margin_m must be >= 0");
  need(std::isfinite(connect_gap_m) && connect_gap_m >= 0.0,
       "LaserOdometryConfig: connect_gap_m must be >= 0");
  for (double v : {odom_std_m, odom_std_rad})
    need(std::isfinite(v) && v > 0.0, "LaserOdometryConfig: odom_std_m and odom_std_rad must be > 0");
  need(std::isfinite(min_match_information) && min_match_information >= 0.0,
       "LaserOdometryConfig: min_match_information must be >= 0");
  need(min_match_information == 0.0 || connect_gap_m > 0.0,
       "LaserOdometryConfig: connect_gap_m must be > 0 when min_match_information > 0 (the match's "
       "information comes from the walls through neighbouring returns)");
  need(std::isfinite(odometry_gate_chi2) && odometry_gate_chi2 > 0.0,
       "LaserOdometryConfig: odometry_gate_chi2 must be > 0");
  need(std::isfinite(odometry_gate_min_score) && odometry_gate_min_score >= 0.0 &&
           odometry_gate_min_score <= 1.0,
       "LaserOdometryConfig: odometry_gate_min_score must be in [0, 1]");
  for (double v : {odom_std_per_m, odom_std_per_rad})
    need(std::isfinite(v) && v >= 0.0,
         "LaserOdometryConfig: odom_std_per_m and odom_std_per_rad must be >= 0");
}

LikelihoodField::LikelihoodField(const std::vector<Eigen::Vector2d>& points_m, double resolution_m,
                                 double hit_std_m, double margin_m, double connect_gap_m)
    : resolution_m_(resolution_m) {
  if (points_m.empty()) throw std::invalid_argument("LikelihoodField: no map point");
  Eigen::Vector2d lo = points_m.front(), hi = points_m.front();
  for (const auto& p : points_m) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo.array() -= margin_m;
  hi.array() += margin_m;
  const int w = static_cast<int>(std::ceil((hi.x() - lo.x()) / resolution_m)) + 1;
  const int h = static_cast<int>(std::ceil((hi.y() - lo.y()) / resolution_m)) + 1;
  if (w > 4096 || h > 4096)
    throw std::invalid_argument("LikelihoodField: the map points span more than 4096 cells");
  origin_m_ = lo;
  cv::Mat free(h, w, CV_8UC1, cv::Scalar(255));  // 0 at map points
  const auto cell = [&](const Eigen::Vector2d& p) {
    return cv::Point(static_cast<int>(std::lround((p.x() - lo.x()) / resolution_m)),
                     static_cast<int>(std::lround((p.y() - lo.y()) / resolution_m)));
  };
  const double gap2 = connect_gap_m * connect_gap_m;
  for (size_t i = 0; i < points_m.size(); ++i) {
    const cv::Point c = cell(points_m[i]);
    if (c.x >= 0 && c.x < w && c.y >= 0 && c.y < h) free.at<uchar>(c) = 0;
    if (i > 0 && (points_m[i] - points_m[i - 1]).squaredNorm() < gap2)
      cv::line(free, cell(points_m[i - 1]), c, cv::Scalar(0), 1, cv::LINE_8);
  }
  // Each map cell stamps exp(-d^2 / (2 hit_std^2)) over the cells within kFieldRadiusStd
  // hit_std of it, the largest value kept: what the exact distance transform of the whole box
  // gives, cut where it falls below exp(-8), at a cost that grows with the map cells rather than
  // with the box's area (a local map over a hall is a million cells, most of them empty).
  const int r =
      std::max(1, static_cast<int>(std::ceil(kFieldRadiusStd * hit_std_m / resolution_m)));
  const double k = -0.5 * (resolution_m * resolution_m) / (hit_std_m * hit_std_m);
  cv::Mat kernel(2 * r + 1, 2 * r + 1, CV_32F);
  for (int y = -r; y <= r; ++y)
    for (int x = -r; x <= r; ++x)
      kernel.at<float>(y + r, x + r) = static_cast<float>(std::exp(k * (x * x + y * y)));
  std::vector<cv::Point> occupied;
  cv::findNonZero(free == 0, occupied);
  field_ = cv::Mat::zeros(h, w, CV_32F);
  for (const cv::Point& c : occupied) {
    const int x_lo = std::max(0, c.x - r), x_hi = std::min(w - 1, c.x + r);
    for (int y = std::max(0, c.y - r); y <= std::min(h - 1, c.y + r); ++y) {
      float* f = field_.ptr<float>(y);
      const float* kr = kernel.ptr<float>(y - c.y + r) + (x_lo - c.x + r);
      for (int x = x_lo; x <= x_hi; ++x, ++kr) f[x] = std::max(f[x], *kr);
    }
  }
}

double LikelihoodField::at(const Eigen::Vector2d& p) const {
  const double fx = (p.x() - origin_m_.x()) / resolution_m_;
  const double fy = (p.y() - origin_m_.y()) / resolution_m_;
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= field_.cols || y0 + 1 >= field_.rows) return 0.0;
  const double ax = fx - x0, ay = fy - y0;
  const float* r0 = field_.ptr<float>(y0);
  const float* r1 = field_.ptr<float>(y0 + 1);
  return (1 - ay) * ((1 - ax) * r0[x0] + ax * r0[x0 + 1]) +
         ay * ((1 - ax) * r1[x0] + ax * r1[x0 + 1]);
}

double LikelihoodField::score(const std::vector<Eigen::Vector2d>& points_robot,
                              const math::SE2& pose) const {
  if (points_robot.empty()) return 0.0;
  const double c = std::cos(pose.yaw_rad), sn = std::sin(pose.yaw_rad);
  double s = 0.0;
  for (const auto& p : points_robot)
    s += at(Eigen::Vector2d(pose.x_m + c * p.x() - sn * p.y(), pose.y_m + sn * p.x() + c * p.y()));
  return s / points_robot.size();
}

ScanMatch matchScan(const LikelihoodField& field, const std::vector<Eigen::Vector2d>& points_robot,
                    const math::SE2& prior, const ScanMatcherConfig& c) {
  if (points_robot.empty()) return {prior, 0.0};
  const double res = field.resolution();
  const double inv_xy2 = c.search_xy_m > 0 ? 1.0 / (c.search_xy_m * c.search_xy_m) : 0.0;
  const double inv_yaw2 = c.search_yaw_rad > 0 ? 1.0 / (c.search_yaw_rad * c.search_yaw_rad) : 0.0;
  const auto pull = [&](double dx, double dy, double dyaw) {
    return c.prior_penalty * ((dx * dx + dy * dy) * inv_xy2 + dyaw * dyaw * inv_yaw2);
  };
  const auto objective = [&](const math::SE2& p) {
    return field.score(points_robot, p) -
           pull(p.x_m - prior.x_m, p.y_m - prior.y_m, math::angleDiff(p.yaw_rad, prior.yaw_rad));
  };
  math::SE2 best_pose = prior;
  double best = objective(prior);
  const int k = static_cast<int>(std::floor(c.search_xy_m / res));
  const int side = 2 * k + 1;
  const cv::Mat& f = field.values();
  const int yaw_steps = static_cast<int>(std::floor(c.search_yaw_rad / c.yaw_step_rad));
  std::vector<float> acc(side * side);  // sums of at most a few thousand values in [0, 1]
  const Eigen::Vector2d origin = field.origin();
  const double n = static_cast<double>(points_robot.size());
  for (int yi = -yaw_steps; yi <= yaw_steps; ++yi) {
    const double dyaw = yi * c.yaw_step_rad;
    const double yaw = prior.yaw_rad + dyaw;
    const double cs = std::cos(yaw), sn = std::sin(yaw);
    std::fill(acc.begin(), acc.end(), 0.0);
    for (const auto& p : points_robot) {
      const double wx = prior.x_m + cs * p.x() - sn * p.y();
      const double wy = prior.y_m + sn * p.x() + cs * p.y();
      const int cx = static_cast<int>(std::lround((wx - origin.x()) / res));
      const int cy = static_cast<int>(std::lround((wy - origin.y()) / res));
      const int x_lo = std::max(0, cx - k), x_hi = std::min(f.cols - 1, cx + k);
      if (x_lo > x_hi) continue;
      for (int dy = -k; dy <= k; ++dy) {
        const int y = cy + dy;
        if (y < 0 || y >= f.rows) continue;
        const float* row = f.ptr<float>(y);
        float* a = &acc[(dy + k) * side + (x_lo - cx + k)];
        for (int x = x_lo; x <= x_hi; ++x) *a++ += row[x];
      }
    }
    for (int idx = 0; idx < side * side; ++idx) {
      const double dx = (idx % side - k) * res, dy = (idx / side - k) * res;
      const double v = acc[idx] / n - pull(dx, dy, dyaw);
      if (v > best) {
        best = v;
        best_pose = math::SE2(prior.x_m + dx, prior.y_m + dy, yaw);
      }
    }
  }
  // Refinement on the interpolated field.
  double step_xy = 0.5 * res, step_yaw = 0.5 * c.yaw_step_rad;
  best = objective(best_pose);
  while (step_xy > 0.01 * res) {
    bool moved = false;
    for (int d = 0; d < 6; ++d) {
      math::SE2 t = best_pose;
      const double sgn = d % 2 == 0 ? 1.0 : -1.0;
      if (d < 2) t.x_m += sgn * step_xy;
      else if (d < 4) t.y_m += sgn * step_xy;
      else t = math::SE2(t.x_m, t.y_m, t.yaw_rad + sgn * step_yaw);
      const double v = objective(t);
      if (v > best) {
        best = v;
        best_pose = t;
        moved = true;
      }
    }
    if (!moved) {
      step_xy *= 0.5;
      step_yaw *= 0.5;
    }
  }
  return {best_pose, field.score(points_robot, best_pose)};
}

Eigen::Matrix3d matchInformation(const LikelihoodField& field,
                                 const std::vector<Eigen::Vector2d>& points_robot,
                                 const math::SE2& pose) {
  const double h[3] = {0.5 * field.resolution(), 0.5 * field.resolution(), 0.005};
  const auto at = [&](const Eigen::Vector3d& d) {
    return field.score(points_robot, math::SE2(pose.x_m + d.x(), pose.y_m + d.y(),
                                               pose.yaw_rad + d.z()));
  };
  const double f0 = at(Eigen::Vector3d::Zero());
  Eigen::Matrix3d H;
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) {
      Eigen::Vector3d ea = Eigen::Vector3d::Zero(), eb = Eigen::Vector3d::Zero();
      ea(a) = h[a];
      eb(b) = h[b];
      const double v = a == b ? (at(ea) - 2.0 * f0 + at(-ea)) / (h[a] * h[a])
                              : (at(ea + eb) - at(ea - eb) - at(eb - ea) + at(-ea - eb)) /
                                    (4.0 * h[a] * h[b]);
      H(a, b) = H(b, a) = -v;
    }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(H);
  const Eigen::Vector3d lambda = es.eigenvalues().cwiseMax(0.0);
  return static_cast<double>(points_robot.size()) * es.eigenvectors() * lambda.asDiagonal() *
         es.eigenvectors().transpose();
}

Eigen::Matrix3d geometricMatchInformation(const LikelihoodField& field,
                                          const std::vector<Eigen::Vector2d>& points_robot,
                                          const math::SE2& pose, double hit_std_m,
                                          double wall_gap_m) {
  // A neighbourhood is a line when its scatter's smaller eigenvalue is below this share of the
  // larger: 1.5 cm of noise on 0.6 m of wall gives about 0.008, a right-angle corner 0.3 or more.
  constexpr double kLineShare = 0.1;
  const int n = static_cast<int>(points_robot.size());
  const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
  const double gap2 = wall_gap_m * wall_gap_m;
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d& p = points_robot[i];
    if (!p.allFinite()) continue;
    // d(R p)/dyaw in the map frame: R p turned by a quarter.
    const Eigen::Vector2d rp(c * p.x() - s * p.y(), s * p.x() + c * p.y());
    const Eigen::Vector2d drp(-rp.y(), rp.x());
    const double w = field.at(Eigen::Vector2d(pose.x_m, pose.y_m) + rp);
    if (!(w > 0.0)) continue;
    // The wall through p: the consecutive points within wall_gap_m of their predecessor and of p,
    // however many (a dense laser's returns a few mm apart: a span of wall long against the range
    // noise, so that a noisy wall is not taken for a corner).
    Eigen::Vector2d sum = p;
    Eigen::Matrix2d outer = p * p.transpose();
    int count = 1;
    for (int dir : {-1, 1}) {
      Eigen::Vector2d last = p;
      for (int j = i + dir; j >= 0 && j < n; j += dir) {
        const Eigen::Vector2d& q = points_robot[j];
        if (!((q - last).squaredNorm() <= gap2 && (q - p).squaredNorm() <= gap2)) break;
        last = q;
        sum += last;
        outer += last * last.transpose();
        ++count;
      }
    }
    // Fewer than three returns (a wall sampled sparser than wall_gap_m) or no line through them
    // (a corner, clutter): the direction of the surface is not known, and the return tells
    // nothing (the information is a lower bound, as degenerate directions need).
    if (count < 3) continue;
    const Eigen::Vector2d mean = sum / count;
    const Eigen::Matrix2d cov = outer / count - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
    if (!(es.eigenvalues()(0) <= kLineShare * es.eigenvalues()(1))) continue;
    const Eigen::Vector2d nr = es.eigenvectors().col(0);  // the normal, robot frame
    const Eigen::Vector2d nm(c * nr.x() - s * nr.y(), s * nr.x() + c * nr.y());
    const Eigen::Vector3d J(nm.x(), nm.y(), nm.dot(drp));
    const Eigen::Matrix3d Hi = J * J.transpose();
    H += w * Hi;
  }
  return H / (hit_std_m * hit_std_m);
}

LaserOdometry::LaserOdometry(LaserOdometryConfig config) : config_(config) { config_.validate(); }

void LaserOdometry::reset() {
  keyframes_.clear();
  field_.clear();
  started_ = false;
  farthest_seen_m_ = 0.0;
  pose_ = last_odom_ = last_step_ = math::SE2();
  last_score_ = 0.0;
  last_matched_ = false;
  last_degenerate_ = 0;
  last_information_.setZero();
}

Eigen::Vector3d LaserOdometry::odometryStd(const math::SE2& step) const {
  const double sd_xy =
      config_.odom_std_m + config_.odom_std_per_m * std::hypot(step.x_m, step.y_m);
  const double sd_yaw = config_.odom_std_rad + config_.odom_std_per_rad * std::fabs(step.yaw_rad);
  return {sd_xy, sd_xy, sd_yaw};
}

void LaserOdometry::setOdometryInformation(const math::SE2& step) {
  last_information_ = odometryStd(step).array().square().inverse().matrix().asDiagonal();
}

void LaserOdometry::rebuildField() {
  std::vector<Eigen::Vector2d> pts;
  for (const Keyframe& k : keyframes_)
    for (const auto& p : k.points_robot) pts.push_back(k.pose.transformPoint(p));
  field_.clear();
  if (!pts.empty())
    field_.emplace_back(pts, config_.matcher.resolution_m, config_.matcher.hit_std_m,
                        config_.matcher.search_xy_m + 1.0, config_.connect_gap_m);
}

math::SE2 LaserOdometry::add(const std::vector<Eigen::Vector2d>& points_robot,
                             const math::SE2& odom) {
  ++scans_;
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(points_robot.size());
  const double r2 = config_.max_range_m * config_.max_range_m;
  for (const auto& p : points_robot) {
    if (!p.allFinite()) continue;
    const double d2 = p.squaredNorm();
    farthest_seen_m_ = std::max(farthest_seen_m_, std::sqrt(d2));
    if (d2 <= r2) pts.push_back(p);
  }
  // The points matched: all of pts, but for a sensor that reaches less far than max_range_m, not
  // those within edge_margin_m of its reach (they go into the map all the same).
  std::vector<Eigen::Vector2d> query;
  const double reach_m = farthest_seen_m_ - config_.edge_margin_m;
  if (farthest_seen_m_ < config_.max_range_m) {
    query.reserve(pts.size());
    for (const auto& p : pts)
      if (p.squaredNorm() <= reach_m * reach_m) query.push_back(p);
  } else {
    query = pts;
  }
  if (!started_) {
    started_ = true;
    pose_ = odom;
    last_odom_ = odom;
    last_score_ = 0.0;
    last_matched_ = false;
    if (static_cast<int>(pts.size()) >= config_.min_points) {
      keyframes_.push_back({pose_, pts});
      rebuildField();
    }
    return pose_;
  }
  const math::SE2 odom_step = math::between(last_odom_, odom);
  last_odom_ = odom;
  last_matched_ = false;
  last_score_ = 0.0;
  last_degenerate_ = 0;
  // The priors the match starts from: the wheel odometry's increment, and when that differs from
  // the last increment by more than the search window (odometry that stalls and then jumps: in
  // the mit-csail log it stands still for 0.8 s while the robot turns, then catches up by 85
  // degrees at once), also the last increment again (constant velocity) and no motion. The best
  // match wins; the odometry's on a tie.
  std::vector<math::SE2> priors{pose_ * odom_step};
  const math::SE2 change = math::between(last_step_, odom_step);
  if (std::hypot(change.x_m, change.y_m) > config_.matcher.search_xy_m ||
      std::fabs(change.yaw_rad) > config_.matcher.search_yaw_rad) {
    priors.push_back(pose_ * last_step_);
    priors.push_back(pose_);
  }
  math::SE2 prior = priors.front();
  if (static_cast<int>(query.size()) >= config_.min_points && !field_.empty()) {
    ScanMatch m;
    m.score = -1.0;
    for (const math::SE2& candidate : priors) {
      const ScanMatch c = matchScan(field_.front(), query, candidate, config_.matcher);
      if (c.score > m.score) {
        m = c;
        prior = candidate;
      }
    }
    last_score_ = m.score;
    if (m.score >= config_.min_score) {
      // Fuse the match with the prior by their information, in the prior's tangent space, each
      // along the directions that whiten both: P^1/2 H P^1/2 = V diag(lambda) V^T, the
      // generalised eigenproblem H v = lambda P^-1 v. Along v_i the scan's information is lambda_i
      // times the odometry's; the disagreement whitened by the odometry's deviation is z.
      const Eigen::Vector3d sd = odometryStd(math::between(pose_, prior));
      const Eigen::Matrix3d H = geometricMatchInformation(
          field_.front(), query, m.pose, config_.matcher.hit_std_m, config_.connect_gap_m);
      const Eigen::Vector3d dm(m.pose.x_m - prior.x_m, m.pose.y_m - prior.y_m,
                               math::angleDiff(m.pose.yaw_rad, prior.yaw_rad));
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(sd.asDiagonal() * H *
                                                              sd.asDiagonal());
      const Eigen::Matrix3d V = es.eigenvectors();
      const Eigen::Vector3d lambda = es.eigenvalues().cwiseMax(0.0);
      const Eigen::Vector3d z = V.transpose() * dm.cwiseQuotient(sd);
      // The disagreement's chi-square, dm^T (P + H^-1)^-1 dm = sum lambda_i / (1 + lambda_i) z_i^2,
      // over the well-constrained directions only: along a degenerate one the match's value is
      // arbitrary (anywhere in the search window) and says nothing about the odometry.
      bool constrained[3];
      double chi2 = 0.0;
      last_degenerate_ = 0;
      for (int i = 0; i < 3; ++i) {
        constrained[i] = lambda(i) >= config_.min_match_information;
        if (constrained[i]) chi2 += lambda(i) / (1.0 + lambda(i)) * z(i) * z(i);
        else ++last_degenerate_;
      }
      const bool gated = chi2 > config_.odometry_gate_chi2;
      const bool weak = gated && m.score < config_.odometry_gate_min_score;
      if (weak) {
        prior = priors.front();  // a weak match against the odometry: the odometry alone
        ++weak_rejected_;
        setOdometryInformation(math::between(pose_, prior));
      } else {
        // Along each well-constrained direction the match alone when the odometry disagrees
        // beyond its noise (it slipped, stalled or jumped), else the two fused; along a
        // degenerate one the prior's value (the match's is arbitrary there).
        Eigen::Vector3d w, info_w;
        for (int i = 0; i < 3; ++i) {
          w(i) = !constrained[i] ? 0.0 : gated ? 1.0 : lambda(i) / (1.0 + lambda(i));
          info_w(i) = !constrained[i] ? 1.0 : gated ? lambda(i) : 1.0 + lambda(i);
        }
        const Eigen::Vector3d d = sd.cwiseProduct(V * w.cwiseProduct(z));
        prior = math::SE2(prior.x_m + d.x(), prior.y_m + d.y(), prior.yaw_rad + d.z());
        const Eigen::Vector3d inv_sd = sd.cwiseInverse();
        last_information_ =
            inv_sd.asDiagonal() * V * info_w.asDiagonal() * V.transpose() * inv_sd.asDiagonal();
        if (gated) ++odometry_rejected_;
      }
      last_matched_ = !weak;
      matched_ += last_matched_ ? 1 : 0;
    } else {
      prior = priors.front();  // no match to trust: the wheel odometry
      setOdometryInformation(math::between(pose_, prior));
    }
  } else {
    setOdometryInformation(math::between(pose_, prior));
  }
  last_step_ = math::between(pose_, prior);
  pose_ = prior;
  const math::SE2 since = keyframes_.empty() ? math::SE2(1e9, 0, 0)
                                             : math::between(keyframes_.back().pose, pose_);
  if (static_cast<int>(pts.size()) >= config_.min_points &&
      (std::hypot(since.x_m, since.y_m) >= config_.keyframe_translation_m ||
       std::fabs(since.yaw_rad) >= config_.keyframe_rotation_rad)) {
    keyframes_.push_back({pose_, std::move(pts)});
    while (static_cast<int>(keyframes_.size()) > config_.local_map_keyframes) keyframes_.pop_front();
    rebuildField();
  }
  return pose_;
}

}  // namespace adaptive_perception::slam
