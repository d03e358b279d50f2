#include "adaptive_perception/slam/line_ekf_slam.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/chi_square.h"

namespace adaptive_perception::slam {

Association parseAssociation(const std::string& name) {
  if (name == "nn") return Association::kNearestNeighbour;
  if (name == "jcbb") return Association::kJcbb;
  throw std::invalid_argument("association = '" + name + "' (allowed: nn, jcbb)");
}

void LineEkfSlamConfig::validate() const {
  auto check = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument(what);
  };
  check(gate_probability > 0.0 && gate_probability < 1.0,
        "gate_probability = " + std::to_string(gate_probability) + " (allowed: 0 < p < 1)");
  check(confirm_sightings >= 1,
        "confirm_sightings = " + std::to_string(confirm_sightings) + " (allowed: >= 1)");
  check(
      tentative_timeout_scans >= 1,
      "tentative_timeout_scans = " + std::to_string(tentative_timeout_scans) + " (allowed: >= 1)");
  check(min_new_line_length_m >= 0.0, "min_new_line_length_m must be >= 0");
  for (double a : {alpha1, alpha2, alpha3, alpha4, min_translation_std_m, min_rotation_std_rad})
    check(a >= 0.0 && std::isfinite(a), "odometry noise parameters must be finite and >= 0");
}

LineEkfSlam::LineEkfSlam(const LineEkfSlamConfig& config, const math::SE2& start,
                         const Eigen::Matrix3d& start_cov)
    : config_(config), x_(3), p_(start_cov) {
  config_.validate();
  x_ << start.x_m, start.y_m, math::wrapAngle(start.yaw_rad);
}

Eigen::Matrix3d LineEkfSlam::odometryNoise(const math::SE2& d) const {
  const double t = std::hypot(d.x_m, d.y_m), r = std::fabs(d.yaw_rad);
  const double st = config_.alpha3 * t + config_.alpha4 * r + config_.min_translation_std_m;
  const double sr = config_.alpha1 * r + config_.alpha2 * t + config_.min_rotation_std_rad;
  return Eigen::Vector3d(st * st, st * st, sr * sr).asDiagonal();
}

void LineEkfSlam::predict(const math::SE2& d) { predict(d, odometryNoise(d)); }

void LineEkfSlam::predict(const math::SE2& d, const Eigen::Matrix3d& q) {
  Eigen::Matrix3d fx, fv;
  const math::SE2 next = predictPose(pose(), d, &fx, &fv);
  x_.head<3>() << next.x_m, next.y_m, next.yaw_rad;
  const int n = static_cast<int>(x_.size());
  // Only the pose rows/columns change: P_rr = F P_rr F^T + F_v Q F_v^T, P_rl = F P_rl.
  p_.topLeftCorner<3, 3>() =
      fx * p_.topLeftCorner<3, 3>() * fx.transpose() + fv * q * fv.transpose();
  if (n > 3) {
    p_.topRightCorner(3, n - 3) = fx * p_.topRightCorner(3, n - 3);
    p_.bottomLeftCorner(n - 3, 3) = p_.topRightCorner(3, n - 3).transpose();
  }
}

void LineEkfSlam::stack(const std::vector<LineObservation>& obs, const std::vector<Pairing>& pairs,
                        Eigen::VectorXd* nu, Eigen::MatrixXd* h, Eigen::MatrixXd* r) const {
  const int m = static_cast<int>(pairs.size()), n = static_cast<int>(x_.size());
  nu->resize(2 * m);
  h->setZero(2 * m, n);
  r->setZero(2 * m, 2 * m);
  for (int k = 0; k < m; ++k) {
    Eigen::Matrix<double, 2, 3> hr;
    Eigen::Matrix2d hl;
    const Line pred = observeLine(pose(), landmark(pairs[k].lm), &hr, &hl);
    nu->segment<2>(2 * k) = lineInnovation(obs[pairs[k].obs].line, pred);
    h->block<2, 3>(2 * k, 0) = hr;
    h->block<2, 2>(2 * k, landmarkIndex(pairs[k].lm)) = hl;
    r->block<2, 2>(2 * k, 2 * k) = obs[pairs[k].obs].cov;
  }
}

double LineEkfSlam::jointMahalanobis(const std::vector<LineObservation>& obs,
                                     const std::vector<Pairing>& pairs) const {
  if (pairs.empty()) return 0.0;
  Eigen::VectorXd nu;
  Eigen::MatrixXd h, r;
  stack(obs, pairs, &nu, &h, &r);
  const Eigen::MatrixXd s = h * p_ * h.transpose() + r;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(s);
  return nu.dot(ldlt.solve(nu));
}

void LineEkfSlam::jcbb(const std::vector<LineObservation>& obs,
                       const std::vector<std::vector<int>>& candidates, size_t i,
                       std::vector<Pairing>& current, std::vector<Pairing>& best, double& best_d2,
                       long& nodes) const {
  ++nodes;
  if (i == obs.size()) {
    const double d2 = jointMahalanobis(obs, current);
    if (current.size() > best.size() || (current.size() == best.size() && d2 < best_d2)) {
      best = current;
      best_d2 = d2;
    }
    return;
  }
  // Bound: even pairing every remaining observation cannot beat the best.
  if (current.size() + (obs.size() - i) < best.size()) return;
  for (int lm : candidates[i]) {
    bool used = false;
    for (const auto& p : current) used |= p.lm == lm;
    if (used) continue;
    current.push_back({static_cast<int>(i), lm});
    const int dof = 2 * static_cast<int>(current.size());
    if (jointMahalanobis(obs, current) <= math::chiSquareQuantile(config_.gate_probability, dof))
      jcbb(obs, candidates, i + 1, current, best, best_d2, nodes);
    current.pop_back();
  }
  // The null hypothesis for observation i (new or spurious line).
  if (current.size() + (obs.size() - i - 1) >= best.size())
    jcbb(obs, candidates, i + 1, current, best, best_d2, nodes);
}

std::vector<int> LineEkfSlam::associate(const std::vector<LineObservation>& obs) const {
  const double gate2 = math::chiSquareQuantile(config_.gate_probability, 2);
  std::vector<std::vector<int>> candidates(obs.size());
  std::vector<std::vector<double>> d2s(obs.size());
  for (size_t i = 0; i < obs.size(); ++i) {
    for (int j = 0; j < numLandmarks(); ++j) {
      const double d2 = jointMahalanobis(obs, {{static_cast<int>(i), j}});
      if (d2 <= gate2) {
        candidates[i].push_back(j);
        d2s[i].push_back(d2);
      }
    }
    // Most compatible first: JCBB then finds good hypotheses early and prunes more.
    std::vector<size_t> order(candidates[i].size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(),
              [&](size_t a, size_t b) { return d2s[i][a] < d2s[i][b]; });
    std::vector<int> c;
    std::vector<double> d;
    for (size_t k : order) {
      c.push_back(candidates[i][k]);
      d.push_back(d2s[i][k]);
    }
    candidates[i] = c;
    d2s[i] = d;
  }
  std::vector<int> out(obs.size(), -1);
  if (config_.association == Association::kNearestNeighbour) {
    for (size_t i = 0; i < obs.size(); ++i)
      if (!candidates[i].empty()) out[i] = candidates[i].front();
    return out;
  }
  std::vector<Pairing> current, best;
  double best_d2 = std::numeric_limits<double>::infinity();
  long nodes = 0;
  jcbb(obs, candidates, 0, current, best, best_d2, nodes);
  for (const auto& p : best) out[p.obs] = p.lm;
  return out;
}

void LineEkfSlam::extendExtent(int i, const LineObservation& obs) {
  // Endpoints to map, projected on the landmark line, merged with the extent along its direction.
  const math::SE2 r = pose();
  const double c = std::cos(r.yaw_rad), s = std::sin(r.yaw_rad);
  auto to_map = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(r.x_m + c * p.x() - s * p.y(), r.y_m + s * p.x() + c * p.y());
  };
  const Line l = landmark(i);
  const Eigen::Vector2d n(std::cos(l.alpha_rad), std::sin(l.alpha_rad)), t(-n.y(), n.x());
  const Eigen::Vector2d foot = l.rho_m * n;
  Landmark& lm = landmarks_[i];
  std::vector<double> u{t.dot(to_map(obs.start_m) - foot), t.dot(to_map(obs.end_m) - foot)};
  if (lm.sightings > 0) {
    u.push_back(t.dot(lm.start_m - foot));
    u.push_back(t.dot(lm.end_m - foot));
  }
  const auto [lo, hi] = std::minmax_element(u.begin(), u.end());
  lm.start_m = foot + *lo * t;
  lm.end_m = foot + *hi * t;
}

void LineEkfSlam::addLandmark(const LineObservation& obs, int scan) {
  Eigen::Matrix<double, 2, 3> gr;
  Eigen::Matrix2d gz;
  const Line l = lineToMap(pose(), obs.line, &gr, &gz);
  const int n = static_cast<int>(x_.size());
  x_.conservativeResize(n + 2);
  x_.segment<2>(n) << l.rho_m, l.alpha_rad;
  Eigen::MatrixXd p(n + 2, n + 2);
  p.topLeftCorner(n, n) = p_;
  // Cross-covariance with everything: G_r P_r*.
  p.block(n, 0, 2, n) = gr * p_.topRows(3);
  p.block(0, n, n, 2) = p.block(n, 0, 2, n).transpose();
  p.block<2, 2>(n, n) =
      gr * p_.topLeftCorner<3, 3>() * gr.transpose() + gz * obs.cov * gz.transpose();
  p_ = std::move(p);
  Landmark lm;
  lm.id = next_id_++;
  lm.last_seen_scan = scan;
  landmarks_.push_back(lm);
  extendExtent(numLandmarks() - 1, obs);
  landmarks_.back().sightings = 1;
  landmarks_.back().confirmed_flag = config_.confirm_sightings <= 1;
}

void LineEkfSlam::removeLandmark(int i) {
  const int n = static_cast<int>(x_.size()), k = landmarkIndex(i);
  std::vector<int> keep;
  for (int j = 0; j < n; ++j)
    if (j != k && j != k + 1) keep.push_back(j);
  Eigen::VectorXd x(n - 2);
  Eigen::MatrixXd p(n - 2, n - 2);
  for (int a = 0; a < n - 2; ++a) {
    x[a] = x_[keep[a]];
    for (int b = 0; b < n - 2; ++b) p(a, b) = p_(keep[a], keep[b]);
  }
  x_ = std::move(x);
  p_ = std::move(p);
  landmarks_.erase(landmarks_.begin() + i);
}

LineEkfSlam::UpdateResult LineEkfSlam::update(const std::vector<LineObservation>& obs) {
  ++scan_;
  UpdateResult res;
  res.association = associate(obs);
  std::vector<Pairing> pairs;
  for (size_t i = 0; i < obs.size(); ++i)
    if (res.association[i] >= 0) pairs.push_back({static_cast<int>(i), res.association[i]});
  if (!pairs.empty()) {
    Eigen::VectorXd nu;
    Eigen::MatrixXd h, r;
    stack(obs, pairs, &nu, &h, &r);
    const Eigen::MatrixXd pht = p_ * h.transpose();  // n x 2m
    const Eigen::MatrixXd s = h * pht + r;
    const Eigen::LLT<Eigen::MatrixXd> llt(s);
    if (llt.info() != Eigen::Success)
      throw std::runtime_error("LineEkfSlam: innovation covariance not positive definite");
    const Eigen::MatrixXd k = llt.solve(pht.transpose()).transpose();  // eq. 7: P H^T S^-1
    x_ += k * nu;                                                      // eq. 8
    // Eq. 9, Joseph form (I - K H) P (I - K H)^T + K R K^T, expanded so it costs O(n^2 m):
    // P - K (H P) - (P H^T) K^T + K (H P H^T + R) K^T.
    const Eigen::MatrixXd khp = k * pht.transpose();
    p_ = p_ - khp - khp.transpose() + k * s * k.transpose();
    p_ = 0.5 * (p_ + p_.transpose());
    x_[2] = math::wrapAngle(x_[2]);
    for (int j = 0; j < numLandmarks(); ++j) {
      double& rho = x_[landmarkIndex(j)];
      double& alpha = x_[landmarkIndex(j) + 1];
      if (rho < 0.0) {  // keep rho >= 0 (flip the sign of the row/column of rho)
        rho = -rho;
        alpha += math::kPi;
        p_.row(landmarkIndex(j)) *= -1.0;
        p_.col(landmarkIndex(j)) *= -1.0;
      }
      alpha = math::wrapAngle(alpha);
    }
    for (const auto& pr : pairs) {
      Landmark& lm = landmarks_[pr.lm];
      ++lm.sightings;
      lm.last_seen_scan = scan_;
      lm.confirmed_flag = lm.confirmed_flag || lm.sightings >= config_.confirm_sightings;
      extendExtent(pr.lm, obs[pr.obs]);
    }
    res.matched = static_cast<int>(pairs.size());
  }
  for (size_t i = 0; i < obs.size(); ++i)
    if (res.association[i] < 0 &&
        (obs[i].end_m - obs[i].start_m).norm() >= config_.min_new_line_length_m) {
      addLandmark(obs[i], scan_);
      ++res.added;
    }
  for (int j = numLandmarks() - 1; j >= 0; --j)
    if (!landmarks_[j].confirmed() &&
        scan_ - landmarks_[j].last_seen_scan >= config_.tentative_timeout_scans) {
      removeLandmark(j);
      ++res.removed;
    }
  return res;
}

}  // namespace adaptive_perception::slam
