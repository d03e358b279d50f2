#pragma once
// The metrics visual place recognition papers report for a query traversal against a reference
// traversal (as VPR-Bench computes them, Zaffar et al., IJCV 2021):
//
//   recall@K                the share of queries with a true reference among their K best
//                           matches;
//   precision-recall curve  of the best match, swept over its confidence: the queries whose
//                           confidence is at least a threshold are answered, precision = right
//                           answers / answered, recall = right answers / all queries;
//   pr_auc                  the area under that curve (trapezoids over recall, the curve starting
//                           at recall 0 with the first point's precision);
//   recall at 100% precision  the largest recall with no wrong answer among the answered.
//
// Every query counts: one without any true reference (outside the ground truth) can never be
// right, so it lowers recall. Ties in confidence are answered together.
#include <vector>

namespace adaptive_perception::places {

struct QueryOutcome {
  std::vector<int> ranked;  // reference indices, best first (at least the K of interest)
  double confidence = 0.0;  // of ranked[0], higher = surer
  int truth_reference = -1;  // -1: no true reference
  int tolerance = 0;         // true: |reference - truth_reference| <= tolerance
  bool rightAt(int k) const;  // a true reference among the first k
};

struct PrPoint {
  double threshold, precision, recall;
};

struct TraversalMetrics {
  int queries = 0;
  double recall_at_1 = 0.0, recall_at_5 = 0.0;
  double pr_auc = 0.0;
  double recall_at_full_precision = 0.0;
  std::vector<PrPoint> curve;  // thresholds from high to low, one point per distinct confidence
};

/// Throws std::invalid_argument on no query or a NaN confidence.
TraversalMetrics scoreTraversal(const std::vector<QueryOutcome>& outcomes);

/// The k smallest entries' indices, smallest first (ties: lower index first).
std::vector<int> smallestK(const std::vector<float>& values, int k);
/// How far the smallest value lies below the others: (mean - min) / standard deviation over all
/// entries, 0 when they are all equal. A scale-free confidence for one query's distances.
double separation(const std::vector<float>& values);

}  // namespace adaptive_perception::places
