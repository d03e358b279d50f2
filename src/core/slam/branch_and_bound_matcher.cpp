#include "adaptive_perception/slam/branch_and_bound_matcher.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>


namespace adaptive_perception::slam {

void BranchAndBoundWindow::validate() const {
  auto need = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("BranchAndBoundWindow: " + what);
  };
  need(std::isfinite(search_xy_m) && search_xy_m >= 0.0 && search_xy_m <= 200.0,
       "search_xy_m must be in [0, 200]");
  need(std::isfinite(search_yaw_rad) && search_yaw_rad >= 0.0 && search_yaw_rad <= M_PI,
       "search_yaw_rad must be in [0, pi]");
  need(std::isfinite(yaw_step_rad) && yaw_step_rad >= 1e-4 && yaw_step_rad <= 0.5,
       "yaw_step_rad must be in [1e-4, 0.5]");
  need(max_bounds >= 0, "max_bounds must be >= 0");
}

BranchAndBoundMatcher::BranchAndBoundMatcher(const LikelihoodField& field, int depth)
    : origin_m_(field.origin()),
      resolution_m_(field.resolution()) {
  if (depth < 0 || depth > 12)
    throw std::invalid_argument("BranchAndBoundMatcher: depth must be in [0, 12]");
  levels_.push_back(field.values().clone());
  // Level d from level d - 1 (h = 2^(d-1)): a block of 2h cells is the larger of its two halves,
  // first along x, then along y. In stored indices (see levels_) that is S_d(i) =
  // max(S_(d-1)(i - h), S_(d-1)(i)), 0 outside S_(d-1).
  for (int d = 1; d <= depth; ++d) {
    const int h = 1 << (d - 1);
    const cv::Mat& prev = levels_.back();
    cv::Mat along_x = cv::Mat::zeros(prev.rows, prev.cols + h, CV_32F);
    for (int y = 0; y < prev.rows; ++y) {
      const float* p = prev.ptr<float>(y);
      float* q = along_x.ptr<float>(y);
      for (int i = 0; i < along_x.cols; ++i) {
        const float a = i - h >= 0 && i - h < prev.cols ? p[i - h] : 0.0f;
        const float b = i < prev.cols ? p[i] : 0.0f;
        q[i] = std::max(a, b);
      }
    }
    cv::Mat next = cv::Mat::zeros(prev.rows + h, prev.cols + h, CV_32F);
    for (int j = 0; j < next.rows; ++j) {
      const float* a = j - h >= 0 && j - h < along_x.rows ? along_x.ptr<float>(j - h) : nullptr;
      const float* b = j < along_x.rows ? along_x.ptr<float>(j) : nullptr;
      float* q = next.ptr<float>(j);
      for (int i = 0; i < next.cols; ++i) q[i] = std::max(a ? a[i] : 0.0f, b ? b[i] : 0.0f);
    }
    levels_.push_back(next);
  }
}

namespace {
struct Candidate {
  int yaw_index;  // into the rotated point sets
  int ox, oy;     // offset in cells
  float score;    // the bound at the candidate's level (the score at level 0)
};
}  // namespace

std::optional<ScanMatch> BranchAndBoundMatcher::match(
    const std::vector<Eigen::Vector2d>& points_robot, const math::SE2& prior,
    const BranchAndBoundWindow& window, double min_score, long* nodes_visited,
    const RotationAmbiguity* ambiguity, bool* ambiguous) const {
  window.validate();
  if (ambiguity && !(std::isfinite(ambiguity->half_width_rad) && ambiguity->half_width_rad >= 0.0 &&
                     std::isfinite(ambiguity->ratio) && ambiguity->ratio >= 0.0))
    throw std::invalid_argument(
        "BranchAndBoundMatcher: RotationAmbiguity's half_width_rad and ratio must be >= 0");
  if (ambiguous) *ambiguous = false;
  if (points_robot.empty()) return std::nullopt;
  const int k = static_cast<int>(std::floor(window.search_xy_m / resolution_m_ + 1e-9));
  const int yaw_steps = static_cast<int>(std::floor(window.search_yaw_rad / window.yaw_step_rad + 1e-9));
  const int n_yaw = 2 * yaw_steps + 1;
  const int n_pts = static_cast<int>(points_robot.size());
  // The points' cells for each yaw, as (x, y) pairs.
  std::vector<std::vector<cv::Point>> cells(n_yaw, std::vector<cv::Point>(n_pts));
  for (int j = 0; j < n_yaw; ++j) {
    const double yaw = prior.yaw_rad + (j - yaw_steps) * window.yaw_step_rad;
    const double c = std::cos(yaw), s = std::sin(yaw);
    for (int i = 0; i < n_pts; ++i) {
      const Eigen::Vector2d& p = points_robot[i];
      const double wx = prior.x_m + c * p.x() - s * p.y();
      const double wy = prior.y_m + s * p.x() + c * p.y();
      cells[j][i] = cv::Point(static_cast<int>(std::lround((wx - origin_m_.x()) / resolution_m_)),
                              static_cast<int>(std::lround((wy - origin_m_.y()) / resolution_m_)));
    }
  }
  long visited = 0;
  const float inv_n = 1.0f / static_cast<float>(n_pts);
  auto bound = [&](const Candidate& cand, int d) {
    ++visited;
    const cv::Mat& level = levels_[d];
    const int shift = (1 << d) - 1;
    float sum = 0.0f;
    for (const cv::Point& c : cells[cand.yaw_index]) {
      const int x = c.x + cand.ox + shift, y = c.y + cand.oy + shift;
      if (x < 0 || y < 0 || x >= level.cols || y >= level.rows) continue;
      sum += level.ptr<float>(y)[x];
    }
    return sum * inv_n;
  };
  const int top = depth();
  const int w_top = 1 << top;
  std::vector<Candidate> candidates;
  for (int j = 0; j < n_yaw; ++j) {
    for (int oy = -k; oy <= k; oy += w_top)
      for (int ox = -k; ox <= k; ox += w_top) {
        Candidate c{j, ox, oy, 0.0f};
        c.score = bound(c, top);
        candidates.push_back(c);
      }
  }
  auto by_score = [](const Candidate& a, const Candidate& b) { return a.score > b.score; };
  std::sort(candidates.begin(), candidates.end(), by_score);

  float best_score = static_cast<float>(min_score);
  std::optional<Candidate> best;
  bool stop_at_first = false, stopped = false;  // the ambiguity descent stops at its first leaf
  bool out_of_budget = false;
  // Depth first, best bound first; a candidate whose bound is no better than the best leaf found
  // so far cannot hold a better one.
  std::function<void(const std::vector<Candidate>&, int)> search =
      [&](const std::vector<Candidate>& list, int d) {
        for (const Candidate& c : list) {
          if (stopped || c.score <= best_score) return;  // sorted: no later one is better
          if (d == 0) {
            best_score = c.score;
            best = c;
            stopped = stop_at_first;
            continue;
          }
          if (window.max_bounds > 0 && visited >= window.max_bounds) {
            out_of_budget = true;
            return;
          }
          const int h = 1 << (d - 1);
          std::vector<Candidate> children;
          for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) {
              Candidate child{c.yaw_index, c.ox + a * h, c.oy + b * h, 0.0f};
              if (child.ox > k || child.oy > k) continue;
              child.score = bound(child, d - 1);
              children.push_back(child);
            }
          std::sort(children.begin(), children.end(), by_score);
          search(children, d - 1);
        }
      };
  search(candidates, top);
  if (!best) {
    if (nodes_visited) *nodes_visited = visited;
    return std::nullopt;
  }
  ScanMatch m;
  m.pose = math::SE2(prior.x_m + best->ox * resolution_m_, prior.y_m + best->oy * resolution_m_,
                     prior.yaw_rad + (best->yaw_index - yaw_steps) * window.yaw_step_rad);
  m.score = best->score;
  if (ambiguity) {
    // The same top level without the yaws within the band about the best's.
    std::vector<Candidate> others;
    for (const Candidate& c : candidates)
      if (std::fabs(math::wrapAngle((c.yaw_index - best->yaw_index) * window.yaw_step_rad)) >
          ambiguity->half_width_rad)
        others.push_back(c);
    const Candidate first = *best;
    best.reset();
    best_score = static_cast<float>(ambiguity->ratio * m.score);
    stop_at_first = true;
    out_of_budget = false;
    search(others, top);
    if (ambiguous) *ambiguous = best.has_value() || out_of_budget;  // undecided counts as ambiguous
    best = first;
  }
  if (nodes_visited) *nodes_visited = visited;
  return m;
}

}  // namespace adaptive_perception::slam
