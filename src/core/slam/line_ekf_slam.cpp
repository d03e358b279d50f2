#include "adaptive_perception/slam/line_ekf_slam.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/symmetric2.h"

namespace adaptive_perception::slam {

const config::EnumNames<Variant>& variants() {
  static const config::EnumNames<Variant> names("variant", {{Variant::kStandard, "standard"},
                                                            {Variant::kAnchor, "anchor"},
                                                            {Variant::kExternal, "external"}});
  return names;
}

Variant parseVariant(const std::string& name) { return variants().parse(name); }
std::string variantName(Variant v) { return variants().name(v); }

LineEkfSlam::LineEkfSlam(const LineEkfSlamConfig& config, const math::SE2& start,
                         const Eigen::Matrix3d& start_cov)
    : config_(config), association_(config.association), x_(3), p_(start_cov), lin_pose_(start) {
  config_.validate();
  x_ << start.x_m, start.y_m, math::wrapAngle(start.yaw_rad);
}

Eigen::Matrix3d LineEkfSlam::odometryNoise(const math::SE2& d) const {
  const Eigen::Vector2d sd = localization::motionNoiseStd(d, config_.motion);
  const double st = sd[0], sr = sd[1];
  return Eigen::Vector3d(st * st, st * st, sr * sr).asDiagonal();
}

std::vector<LineObservation> toObservations(const std::vector<laser::LineSegment>& segments,
                                            const math::SE2& mount) {
  std::vector<LineObservation> out;
  out.reserve(segments.size());
  const double c = std::cos(mount.yaw_rad), sn = std::sin(mount.yaw_rad);
  auto to_base = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(mount.x_m + c * p.x() - sn * p.y(), mount.y_m + sn * p.x() + c * p.y());
  };
  for (const auto& seg : segments) {
    Eigen::Matrix2d gz;
    LineObservation ob;
    ob.line = lineToMap(mount, Line{seg.line.rho_m, seg.line.alpha_rad}, nullptr, &gz);
    ob.cov = gz * seg.line.cov * gz.transpose();
    ob.start_m = to_base(seg.start_m);
    ob.end_m = to_base(seg.end_m);
    out.push_back(ob);
  }
  return out;
}

Eigen::Matrix2d LineEkfSlam::modelNoise() const {
  return Eigen::Vector2d(config_.line_model_rho_std_m * config_.line_model_rho_std_m,
                         config_.line_model_alpha_std_rad * config_.line_model_alpha_std_rad)
      .asDiagonal();
}

bool LineEkfSlam::predictFromOdometry(const math::SE2& odom) {
  const bool had = have_odom_;
  if (had) predict(math::between(last_odom_, odom));
  last_odom_ = odom;
  have_odom_ = true;
  return had;
}

void LineEkfSlam::predict(const math::SE2& d) { predict(d, odometryNoise(d)); }

void LineEkfSlam::predict(const math::SE2& d, const Eigen::Matrix3d& q) {
  Eigen::Matrix3d fx, fv;
  const math::SE2 next = predictPose(pose(), d, &fx, &fv);
  if (config_.first_estimate_jacobians) {
    // F_x from the predicted positions: x_{k+1|k} - x_{k|k-1} instead of R(theta_{k|k}) d.
    fx(0, 2) = -(next.y_m - lin_pose_.y_m);
    fx(1, 2) = next.x_m - lin_pose_.x_m;
  }
  lin_pose_ = next;
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

Eigen::Vector2d LineEkfSlam::linearise(const LineObservation& obs, int lm,
                                       Eigen::Matrix<double, 2, 3>* hr, Eigen::Matrix2d* hl,
                                       Eigen::Matrix2d* r) const {
  const bool fixed = lm >= numLandmarks();
  const FixedLandmark* f = fixed ? &fixed_[lm - numLandmarks()] : nullptr;
  const Line map_line = fixed ? f->line : landmark(lm);
  const Line pred = observeLine(pose(), map_line, hr, hl);
  if (config_.first_estimate_jacobians && !fixed) {
    // Same flip as the prediction (it defines the innovation's representation).
    const double raw_rho = map_line.rho_m - (x_[0] * std::cos(map_line.alpha_rad) +
                                             x_[1] * std::sin(map_line.alpha_rad));
    observeLineJacobians(lin_pose_.x_m, lin_pose_.y_m, landmarks_[lm].first_alpha_rad,
                         raw_rho < 0.0 ? -1.0 : 1.0, hr, hl);
  }
  *r = obs.cov + modelNoise();
  if (fixed) *r += *hl * f->cov * hl->transpose();  // a retired landmark's own uncertainty
  return lineInnovation(obs.line, pred);
}

LinearPairing LineEkfSlam::linearPairing(const LineObservation& obs, int lm) const {
  LinearPairing q;
  q.nu = linearise(obs, lm, &q.hr, &q.hl, &q.r);
  if (lm < numLandmarks()) q.col = landmarkIndex(lm);
  return q;
}

std::vector<int> LineEkfSlam::associate(const std::vector<LineObservation>& obs) const {
  return association_.associate(static_cast<int>(obs.size()), numLandmarks() + numFixedLandmarks(),
                                p_, [&](int i, int lm) { return linearPairing(obs[i], lm); });
}

LineEkfSlam::Block LineEkfSlam::pairingBlock(const LineObservation& obs, int lm) const {
  Block b;
  Eigen::Matrix<double, 2, 3> hr;
  Eigen::Matrix2d hl, r;
  b.nu = linearise(obs, lm, &hr, &hl, &r);
  b.hr = hr;
  b.r = r;
  if (lm < numLandmarks()) {
    b.hl = hl;
    b.col = landmarkIndex(lm);
  }
  return b;
}

std::vector<LineEkfSlam::Block> LineEkfSlam::blocks(const std::vector<LineObservation>& obs,
                                                    const std::vector<Pairing>& pairs) const {
  std::vector<Block> out;
  out.reserve(pairs.size());
  for (const auto& p : pairs) out.push_back(pairingBlock(obs[p.obs], p.lm));
  return out;
}

double LineEkfSlam::applyUpdate(const std::vector<Block>& b) {
  const int n = static_cast<int>(x_.size());
  int d = 0;
  for (const auto& blk : b) d += static_cast<int>(blk.nu.size());
  Eigen::VectorXd nu(d);
  Eigen::MatrixXd pht(n, d);  // P H^T from the non-zero columns of H: O(n d)
  for (size_t k = 0, o = 0; k < b.size(); o += b[k].nu.size(), ++k) {
    const int dk = static_cast<int>(b[k].nu.size());
    nu.segment(o, dk) = b[k].nu;
    pht.middleCols(o, dk) = p_.leftCols(3) * b[k].hr.transpose();
    if (b[k].col >= 0) pht.middleCols(o, dk) += p_.middleCols(b[k].col, 2) * b[k].hl.transpose();
    if (b[k].col2 >= 0) pht.middleCols(o, dk) += p_.middleCols(b[k].col2, 2) * b[k].hl2.transpose();
  }
  // S = H (P H^T) + R from the same P H^T the covariance update uses, so that the expanded Joseph
  // form below stays consistent to round-off.
  Eigen::MatrixXd s(d, d);
  for (size_t k = 0, o = 0; k < b.size(); o += b[k].nu.size(), ++k) {
    const int dk = static_cast<int>(b[k].nu.size());
    s.middleRows(o, dk) = b[k].hr * pht.topRows(3);
    if (b[k].col >= 0) s.middleRows(o, dk) += b[k].hl * pht.middleRows(b[k].col, 2);
    if (b[k].col2 >= 0) s.middleRows(o, dk) += b[k].hl2 * pht.middleRows(b[k].col2, 2);
    s.block(o, o, dk, dk) += b[k].r;
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(s);
  if (llt.info() != Eigen::Success)
    throw std::runtime_error("LineEkfSlam: innovation covariance not positive definite");
  const Eigen::MatrixXd k = llt.solve(pht.transpose()).transpose();  // eq. 7: P H^T S^-1
  x_ += k * nu;                                                      // eq. 6 with innovation eq. 8
  // Eq. 9, Joseph form (I - K H) P (I - K H)^T + K R K^T, expanded so it costs O(n^2 d):
  // P - K (H P) - (P H^T) K^T + K (H P H^T + R) K^T = P + K V^T + V K^T with V = K S / 2 - P H^T,
  // evaluated on the lower triangle only (Eigen's triangular products), then mirrored.
  const Eigen::MatrixXd v = 0.5 * (k * s) - pht;
  p_.triangularView<Eigen::Lower>() += k * v.transpose();
  p_.triangularView<Eigen::Lower>() += v * k.transpose();
  p_.triangularView<Eigen::StrictlyUpper>() = p_.transpose();
  normaliseLandmarks();
  return nu.dot(llt.solve(nu));
}

void LineEkfSlam::normaliseLandmarks() {
  x_[2] = math::wrapAngle(x_[2]);
  for (int j = 0; j < numLandmarks(); ++j) {
    double& rho = x_[landmarkIndex(j)];
    double& alpha = x_[landmarkIndex(j) + 1];
    if (rho < 0.0) {  // keep rho >= 0 (flip the sign of the row/column of rho)
      rho = -rho;
      alpha += math::kPi;
      p_.row(landmarkIndex(j)) *= -1.0;
      p_.col(landmarkIndex(j)) *= -1.0;
      landmarks_[j].first_alpha_rad = math::wrapAngle(landmarks_[j].first_alpha_rad + math::kPi);
    }
    alpha = math::wrapAngle(alpha);
  }
}

double LineEkfSlam::updateExternalPosition(const Eigen::Vector2d& xy_m,
                                           const Eigen::Matrix2d& cov) {
  Block b;  // eqs. 26-27: h = t, H = [I 0]
  b.nu = xy_m - x_.head<2>();
  b.hr = Eigen::Matrix<double, 2, 3>::Identity();
  b.r = cov;
  return applyUpdate({b});
}

double LineEkfSlam::updateExternalPose(const math::SE2& z, const Eigen::Matrix3d& cov) {
  Block b;
  b.nu = Eigen::Vector3d(z.x_m - x_[0], z.y_m - x_[1], math::angleDiff(z.yaw_rad, x_[2]));
  b.hr = Eigen::Matrix3d::Identity();
  b.r = cov;
  return applyUpdate({b});
}

void LineEkfSlam::addLandmark(const LineObservation& obs, int scan) {
  Eigen::Matrix<double, 2, 3> gr;
  Eigen::Matrix2d gz;
  const bool fej = config_.first_estimate_jacobians;
  const Line l = lineToMap(pose(), obs.line, fej ? lin_pose_.x_m : x_[0],
                           fej ? lin_pose_.y_m : x_[1], &gr, &gz);
  const int n = static_cast<int>(x_.size());
  x_.conservativeResize(n + 2);
  x_.segment<2>(n) << l.rho_m, l.alpha_rad;
  Eigen::MatrixXd p(n + 2, n + 2);
  p.topLeftCorner(n, n) = p_;
  // Cross-covariance with everything: G_r P_r*.
  p.block(n, 0, 2, n) = gr * p_.topRows(3);
  p.block(0, n, n, 2) = p.block(n, 0, 2, n).transpose();
  p.block<2, 2>(n, n) = gr * p_.topLeftCorner<3, 3>() * gr.transpose() +
                        gz * (obs.cov + modelNoise()) * gz.transpose();
  p_ = std::move(p);
  Landmark lm;
  lm.id = next_id_++;
  lm.first_alpha_rad = l.alpha_rad;
  lm.last_seen_scan = scan;
  landmarks_.push_back(lm);
  extendExtent(numLandmarks() - 1, obs);
  landmarks_.back().sightings = 1;
  landmarks_.back().confirmed_flag = config_.confirm_sightings <= 1;
}

void LineEkfSlam::removeLandmark(int i) {
  // Drop rows and columns k, k+1 by moving the blocks after them up and left (O(n^2) block copies,
  // no per-element indexing).
  const int n = static_cast<int>(x_.size()), k = landmarkIndex(i), tail = n - k - 2;
  if (tail > 0) {
    x_.segment(k, tail) = x_.tail(tail).eval();
    p_.block(0, k, n, tail) = p_.rightCols(tail).eval();
    p_.block(k, 0, tail, n - 2) = p_.block(k + 2, 0, tail, n - 2).eval();
  }
  x_.conservativeResize(n - 2);
  p_.conservativeResize(n - 2, n - 2);
  landmarks_.erase(landmarks_.begin() + i);
}

void LineEkfSlam::fixLandmark(int i, bool anchor) {
  FixedLandmark f;
  f.info = landmarks_[i];
  f.line = landmark(i);
  f.anchor = anchor;
  const int k = landmarkIndex(i);
  if (anchor) {
    // Condition the state on the landmark being exactly at its estimate: the map frame is now
    // defined by it. The mean is unchanged; P -= P_*l P_ll^-1 P_l*.
    const Eigen::MatrixXd pl = p_.middleCols(k, 2);
    const Eigen::LDLT<Eigen::Matrix2d> ldlt(p_.block<2, 2>(k, k));
    p_ -= pl * ldlt.solve(pl.transpose());
    p_ = 0.5 * (p_ + p_.transpose());
  } else {
    f.cov = p_.block<2, 2>(k, k);  // marginalised: its own uncertainty goes with it
  }
  fixed_.push_back(f);
  removeLandmark(i);
}

double LineEkfSlam::alongFirstAnchor(const Line& anchor, const Line& l) {
  // The intersection p of the two lines, as its coordinate along the anchor: p = rho_a n_a + u t_a
  // with n_a . p = rho_a and n . p = rho, so u = (rho - rho_a n . n_a) / (n . t_a).
  const Eigen::Vector2d na(std::cos(anchor.alpha_rad), std::sin(anchor.alpha_rad)),
      ta(-na.y(), na.x()), n(std::cos(l.alpha_rad), std::sin(l.alpha_rad));
  return (l.rho_m - anchor.rho_m * n.dot(na)) / n.dot(ta);
}

void LineEkfSlam::fixGauge(int j, const Line& anchor) {
  // Condition on u(rho_j, alpha_j) = its estimate, linearised: P -= P J^T (J P J^T)^-1 J P with J
  // the 1x2 derivative of u at landmark j's columns (central differences: u is smooth away from
  // parallel lines, which anchor_min_angle_rad excludes).
  const Line l = landmark(j);
  const double h = 1e-6;
  Eigen::RowVector2d jac;
  jac[0] = (alongFirstAnchor(anchor, Line{l.rho_m + h, l.alpha_rad}) -
            alongFirstAnchor(anchor, Line{l.rho_m - h, l.alpha_rad})) /
           (2 * h);
  jac[1] = (alongFirstAnchor(anchor, Line{l.rho_m, l.alpha_rad + h}) -
            alongFirstAnchor(anchor, Line{l.rho_m, l.alpha_rad - h})) /
           (2 * h);
  const int k = landmarkIndex(j);
  const Eigen::VectorXd pj = p_.middleCols(k, 2) * jac.transpose();  // P J^T
  const double s = jac * p_.block<2, 2>(k, k) * jac.transpose();
  if (s > 0.0) {
    p_ -= pj * pj.transpose() / s;
    p_ = 0.5 * (p_ + p_.transpose());
  }
  landmarks_[j].gauge = true;
}

void LineEkfSlam::anchorOrRetire(UpdateResult* res) {
  if (config_.variant == Variant::kAnchor) {
    // The map frame has three degrees of freedom: the first confirmed line fixes two (its
    // direction and offset) and leaves the state; a second, non-parallel one fixes only the third,
    // the position of its intersection with the first along it, and stays in the state with its
    // direction still estimated. (Fixing the second line whole would assert its angle to the first
    // exactly, an error frozen into every later update.)
    const FixedLandmark* first = nullptr;
    for (const auto& f : fixed_)
      if (f.anchor) first = &f;
    bool have_gauge = false;
    for (const auto& lm : landmarks_) have_gauge |= lm.gauge;
    for (int j = 0; j < numLandmarks() && !first; ++j)
      if (landmarks_[j].confirmed()) {
        fixLandmark(j, true);
        first = &fixed_.back();
        ++res->anchored;
      }
    for (int j = 0; j < numLandmarks() && first && !have_gauge; ++j) {
      // Lines are undirected: directions compare modulo pi.
      if (landmarks_[j].confirmed() &&
          std::fabs(math::wrapAngle(2.0 * (landmark(j).alpha_rad - first->line.alpha_rad))) / 2.0 >=
              config_.anchor_min_angle_rad) {
        fixGauge(j, first->line);
        have_gauge = true;
        ++res->anchored;
      }
    }
  }
  if (config_.retire_after_updates > 0)
    for (int j = numLandmarks() - 1; j >= 0; --j)
      if (landmarks_[j].sightings > config_.retire_after_updates && !landmarks_[j].gauge) {
        fixLandmark(j, false);
        ++res->retired;
      }
}

int LineEkfSlam::mergeCompatible(std::vector<int> seen) {
  const double gate2 = association_.gate(2);
  int merged = 0;
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  while (!seen.empty()) {
    const int i = seen.back();
    seen.pop_back();
    if (!landmarks_[i].confirmed()) continue;
    for (int j = 0; j < numLandmarks(); ++j) {
      if (j == i || !landmarks_[j].confirmed()) continue;
      // Difference d = l_i - F l_j, with F the flip (-rho, alpha + pi) when the normals oppose.
      const Line li = landmark(i), lj = landmark(j);
      const bool flip = std::cos(li.alpha_rad - lj.alpha_rad) < 0.0;
      const Eigen::Matrix2d f = flip ? Eigen::Vector2d(-1.0, 1.0).asDiagonal().toDenseMatrix()
                                     : Eigen::Matrix2d::Identity();
      const Eigen::Vector2d d(
          li.rho_m - (flip ? -lj.rho_m : lj.rho_m),
          math::angleDiff(li.alpha_rad, lj.alpha_rad + (flip ? math::kPi : 0.0)));
      const int ci = landmarkIndex(i), cj = landmarkIndex(j);
      const Eigen::Matrix2d s = p_.block<2, 2>(ci, ci) - p_.block<2, 2>(ci, cj) * f.transpose() -
                                f * p_.block<2, 2>(cj, ci) +
                                f * p_.block<2, 2>(cj, cj) * f.transpose();
      const Eigen::LDLT<Eigen::Matrix2d> ldlt(s);
      if (ldlt.info() != Eigen::Success || !(d.dot(ldlt.solve(d)) <= gate2)) continue;
      // Constrain l_i = F l_j exactly (a pseudo-observation 0 = l_i - F l_j with tiny noise), then
      // drop j: its information already lives in i through the correlation.
      Block b;
      b.nu = -d;
      b.hr = Eigen::Matrix<double, 2, 3>::Zero();
      b.hl = Eigen::Matrix2d::Identity();
      b.col = ci;
      b.hl2 = -f;
      b.col2 = cj;
      b.r = Eigen::Matrix2d::Identity() * 1e-10;
      try {
        applyUpdate({b});
      } catch (const std::runtime_error&) {
        continue;  // numerically degenerate pair: keep both
      }
      Landmark& keep = landmarks_[i];
      const Landmark& gone = landmarks_[j];
      keep.sightings += gone.sightings;
      keep.last_seen_scan = std::max(keep.last_seen_scan, gone.last_seen_scan);
      keep.confirmed_flag = keep.confirmed_flag || gone.confirmed_flag;
      keep.gauge = keep.gauge || gone.gauge;  // l_i = F l_j now: i carries j's fixed intersection
      for (const auto& pc : gone.pieces) {
        LineObservation o;  // pieces are in map: pass them through the robot frame
        const math::SE2 inv = pose().inverse();
        o.start_m = Eigen::Vector2d((inv * math::SE2(pc.first.x(), pc.first.y(), 0.0)).x_m,
                                    (inv * math::SE2(pc.first.x(), pc.first.y(), 0.0)).y_m);
        o.end_m = Eigen::Vector2d((inv * math::SE2(pc.second.x(), pc.second.y(), 0.0)).x_m,
                                  (inv * math::SE2(pc.second.x(), pc.second.y(), 0.0)).y_m);
        extendExtent(i, o);
      }
      removeLandmark(j);
      for (int& k : seen)
        if (k > j) --k;
      ++merged;
      return merged + mergeCompatible(seen);  // indices moved: restart on the rest
    }
  }
  return merged;
}

void LineEkfSlam::addFixedLandmarks(const std::vector<FixedLandmark>& landmarks) {
  for (const FixedLandmark& f : landmarks) {
    if (!std::isfinite(f.line.rho_m) || !std::isfinite(f.line.alpha_rad) ||
        !math::isCovariance(f.cov))
      throw std::invalid_argument("addFixedLandmarks: landmark " + std::to_string(f.info.id) +
                                  " has a non-finite line or a covariance that is not symmetric "
                                  "positive semi-definite");
    fixed_.push_back(f);
    fixed_.back().info.confirmed_flag = true;
    next_id_ = std::max(next_id_, f.info.id + 1);  // landmarks started later get new ids
  }
}

LineEkfSlam::UpdateResult LineEkfSlam::update(const std::vector<LineObservation>& obs) {
  ++scan_;
  UpdateResult res;
  res.association = associate(obs);
  std::vector<Pairing> pairs;
  for (size_t i = 0; i < obs.size(); ++i)
    if (res.association[i] >= 0) pairs.push_back({static_cast<int>(i), res.association[i]});
  if (!pairs.empty()) {
    res.nis = applyUpdate(blocks(obs, pairs));
    res.nis_dof = 2 * static_cast<int>(pairs.size());
    for (const auto& pr : pairs) {
      Landmark& lm =
          pr.lm < numLandmarks() ? landmarks_[pr.lm] : fixed_[pr.lm - numLandmarks()].info;
      if (lm.last_seen_scan != scan_) ++lm.sightings;  // pieces of one wall: one sighting a scan
      lm.last_seen_scan = scan_;
      lm.confirmed_flag = lm.confirmed_flag || lm.sightings >= config_.confirm_sightings;
      extendExtent(pr.lm, obs[pr.obs]);
    }
    res.matched = static_cast<int>(pairs.size());
  }
  for (size_t i = 0; i < obs.size(); ++i)
    if (config_.extend_map && res.association[i] < 0 &&
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
  if (config_.merge_landmarks) {
    // The landmarks matched this scan, by id (removals above shifted the indices).
    std::vector<int> seen;
    for (int j = 0; j < numLandmarks(); ++j)
      if (landmarks_[j].last_seen_scan == scan_) seen.push_back(j);
    res.merged = mergeCompatible(seen);
  }
  anchorOrRetire(&res);
  return res;
}

}  // namespace adaptive_perception::slam
