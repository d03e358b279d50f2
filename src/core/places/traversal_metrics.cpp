#include "adaptive_perception/places/traversal_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>
#include <stdexcept>

namespace adaptive_perception::places {

bool QueryOutcome::rightAt(int k) const {
  if (truth_reference < 0) return false;
  const int n = std::min<int>(k, static_cast<int>(ranked.size()));
  for (int i = 0; i < n; ++i)
    if (std::abs(ranked[i] - truth_reference) <= tolerance) return true;
  return false;
}

TraversalMetrics scoreTraversal(const std::vector<QueryOutcome>& outcomes) {
  if (outcomes.empty()) throw std::invalid_argument("scoreTraversal: no query");
  TraversalMetrics m;
  m.queries = static_cast<int>(outcomes.size());
  const double n = m.queries;
  std::vector<int> order(outcomes.size());
  std::iota(order.begin(), order.end(), 0);
  for (const QueryOutcome& o : outcomes) {
    if (std::isnan(o.confidence)) throw std::invalid_argument("scoreTraversal: NaN confidence");
    m.recall_at_1 += o.rightAt(1);
    m.recall_at_5 += o.rightAt(5);
  }
  m.recall_at_1 /= n;
  m.recall_at_5 /= n;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return outcomes[a].confidence > outcomes[b].confidence;
  });
  long answered = 0, right = 0;
  bool clean = true;
  for (size_t i = 0; i < order.size();) {
    const double t = outcomes[order[i]].confidence;
    for (; i < order.size() && outcomes[order[i]].confidence == t; ++i) {
      ++answered;
      right += outcomes[order[i]].rightAt(1);
    }
    const double precision = static_cast<double>(right) / answered, recall = right / n;
    m.curve.push_back({t, precision, recall});
    if (right < answered) clean = false;
    if (clean) m.recall_at_full_precision = recall;
  }
  double prev_r = 0.0, prev_p = m.curve.front().precision;
  for (const PrPoint& p : m.curve) {
    m.pr_auc += (p.recall - prev_r) * 0.5 * (p.precision + prev_p);
    prev_r = p.recall;
    prev_p = p.precision;
  }
  return m;
}

std::vector<int> smallestK(const std::vector<float>& values, int k) {
  std::vector<int> idx(values.size());
  std::iota(idx.begin(), idx.end(), 0);
  k = std::clamp(k, 0, static_cast<int>(values.size()));
  const auto less = [&](int a, int b) {
    return values[a] < values[b] || (values[a] == values[b] && a < b);
  };
  std::partial_sort(idx.begin(), idx.begin() + k, idx.end(), less);
  idx.resize(k);
  return idx;
}

double separation(const std::vector<float>& values) {
  if (values.empty()) return 0.0;
  double s = 0.0, q = 0.0, lo = values[0];
  for (float v : values) {
    s += v;
    q += static_cast<double>(v) * v;
    lo = std::min<double>(lo, v);
  }
  const double mean = s / values.size();
  const double sd = std::sqrt(std::max(0.0, q / values.size() - mean * mean));
  return sd > 1e-12 * (std::abs(mean) + 1.0) ? (mean - lo) / sd : 0.0;
}

}  // namespace adaptive_perception::places
