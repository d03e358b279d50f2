#include "adaptive_perception/laser/line_evaluation.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/math/chi_square.h"

namespace adaptive_perception::laser {

void LineScore::add(const LineScore& o) {
  extracted += o.extracted;
  extracted_matched += o.extracted_matched;
  truth_eligible += o.truth_eligible;
  truth_matched += o.truth_matched;
  pairs += o.pairs;
  endpoint_error_sum_m += o.endpoint_error_sum_m;
  angle_error_sum_rad += o.angle_error_sum_rad;
  line_nees_sum += o.line_nees_sum;
  line_nees_in_bounds += o.line_nees_in_bounds;
}

LineScore scoreSegments(const std::vector<LineSegment>& extracted,
                        const std::vector<TrueWallPiece>& truth, const LineExtractionConfig& config,
                        double max_offset_m, double max_angle_rad) {
  LineScore sc;
  const double nees_lo = math::chiSquareQuantile(0.025, 2), nees_hi = math::chiSquareQuantile(0.975, 2);
  sc.extracted = static_cast<long>(extracted.size());
  std::vector<bool> hit(truth.size(), false);
  for (const LineSegment& s : extracted) {
    bool found = false;
    for (size_t k = 0; k < truth.size() && !found; ++k) {
      const Eigen::Vector2d a = truth[k].start_m, b = truth[k].end_m;
      const double len = (b - a).norm();
      if (len < 1e-6) continue;
      const Eigen::Vector2d u = (b - a) / len, n(-u.y(), u.x());
      // Endpoints near the wall's line (rho itself is ill-conditioned far from the laser).
      const double off = 0.5 * (std::fabs(n.dot(s.start_m - a)) + std::fabs(n.dot(s.end_m - a)));
      const Eigen::Vector2d sn(std::cos(s.line.alpha_rad), std::sin(s.line.alpha_rad));
      const double dangle =
          std::acos(std::min(1.0, std::fabs(sn.dot(n))));  // between normals, sign-free
      if (off > max_offset_m || dangle > max_angle_rad) continue;
      double s0 = u.dot(s.start_m - a), s1 = u.dot(s.end_m - a);
      if (s0 > s1) std::swap(s0, s1);
      if (std::min(s1, len) - std::max(s0, 0.0) < 0.5 * s.length()) continue;
      found = true;
      if (!hit[k]) {
        hit[k] = true;
        const double e1 = (s.start_m - a).norm() + (s.end_m - b).norm(),
                     e2 = (s.start_m - b).norm() + (s.end_m - a).norm();
        sc.endpoint_error_sum_m += 0.5 * std::min(e1, e2);
        sc.angle_error_sum_rad += dangle;
        ++sc.pairs;
        // The true line in the segment's representation: the normal that points like its own.
        const Eigen::Vector2d tn = n.dot(sn) >= 0.0 ? n : Eigen::Vector2d(-n);
        const Eigen::Vector2d err(s.line.rho_m - tn.dot(a),
                                  math::angleDiff(s.line.alpha_rad, std::atan2(tn.y(), tn.x())));
        const Eigen::LDLT<Eigen::Matrix2d> ldlt(s.line.cov);
        if (ldlt.info() == Eigen::Success && ldlt.isPositive()) {
          const double nees = err.dot(ldlt.solve(err));
          sc.line_nees_sum += nees;
          sc.line_nees_in_bounds += nees >= nees_lo && nees <= nees_hi;
        }
      }
    }
    sc.extracted_matched += found;
  }
  for (size_t k = 0; k < truth.size(); ++k) {
    const double len = (truth[k].end_m - truth[k].start_m).norm();
    if (truth[k].hits < config.min_points || len < config.min_length_m ||
        len / std::max(1, truth[k].hits - 1) > config.max_gap_m)
      continue;
    ++sc.truth_eligible;
    sc.truth_matched += hit[k];
  }
  return sc;
}

}  // namespace adaptive_perception::laser
