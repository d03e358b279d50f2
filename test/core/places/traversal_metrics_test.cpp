// Recall@K, the precision-recall curve, its area and the recall at full precision on cases
// worked out by hand.
#include "adaptive_perception/places/traversal_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace places = adaptive_perception::places;

namespace {

places::QueryOutcome outcome(std::vector<int> ranked, double confidence, int truth, int tol = 0) {
  places::QueryOutcome o;
  o.ranked = std::move(ranked);
  o.confidence = confidence;
  o.truth_reference = truth;
  o.tolerance = tol;
  return o;
}

TEST(TraversalMetrics, RightWithinTheTolerance) {
  const auto o = outcome({7, 3, 9}, 1.0, 5, 2);
  EXPECT_TRUE(o.rightAt(1));   // |7 - 5| = 2
  const auto far = outcome({8, 3, 9}, 1.0, 5, 2);
  EXPECT_FALSE(far.rightAt(1));
  EXPECT_TRUE(far.rightAt(2));  // 3
  EXPECT_FALSE(outcome({0}, 1.0, -1, 100).rightAt(1));  // no true reference: never right
}

TEST(TraversalMetrics, HandWorkedCurve) {
  // Confidences 0.9 (right), 0.8 (wrong, right at 2), 0.7 (right), 0.6 (no truth).
  const std::vector<places::QueryOutcome> q = {outcome({1, 2}, 0.9, 1), outcome({5, 3}, 0.8, 3),
                                               outcome({2, 0}, 0.7, 2), outcome({4, 1}, 0.6, -1)};
  const places::TraversalMetrics m = places::scoreTraversal(q);
  EXPECT_EQ(m.queries, 4);
  EXPECT_DOUBLE_EQ(m.recall_at_1, 0.5);
  EXPECT_DOUBLE_EQ(m.recall_at_5, 0.75);
  ASSERT_EQ(m.curve.size(), 4u);
  // (p, r): (1, 0.25), (0.5, 0.25), (2/3, 0.5), (0.5, 0.5).
  EXPECT_DOUBLE_EQ(m.curve[0].precision, 1.0);
  EXPECT_DOUBLE_EQ(m.curve[0].recall, 0.25);
  EXPECT_DOUBLE_EQ(m.curve[1].precision, 0.5);
  EXPECT_DOUBLE_EQ(m.curve[2].precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(m.curve[2].recall, 0.5);
  EXPECT_DOUBLE_EQ(m.curve[3].precision, 0.5);
  // Area: 0.25 * 1 (from recall 0 at the first precision) + 0 + 0.25 * (0.5 + 2/3) / 2 + 0.
  EXPECT_NEAR(m.pr_auc, 0.25 + 0.25 * (0.5 + 2.0 / 3.0) / 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.recall_at_full_precision, 0.25);
}

TEST(TraversalMetrics, TiedConfidencesAreAnsweredTogether) {
  const std::vector<places::QueryOutcome> q = {outcome({1}, 1.0, 1), outcome({0}, 1.0, 3)};
  const places::TraversalMetrics m = places::scoreTraversal(q);
  ASSERT_EQ(m.curve.size(), 1u);
  EXPECT_DOUBLE_EQ(m.curve[0].precision, 0.5);
  EXPECT_DOUBLE_EQ(m.recall_at_full_precision, 0.0);
}

TEST(TraversalMetrics, PerfectAnswersGiveOne) {
  std::vector<places::QueryOutcome> q;
  for (int i = 0; i < 10; ++i) q.push_back(outcome({i}, 10.0 - i, i));
  const places::TraversalMetrics m = places::scoreTraversal(q);
  EXPECT_DOUBLE_EQ(m.recall_at_1, 1.0);
  EXPECT_DOUBLE_EQ(m.pr_auc, 1.0);
  EXPECT_DOUBLE_EQ(m.recall_at_full_precision, 1.0);
}

TEST(TraversalMetrics, RejectsNoQueryAndNaN) {
  EXPECT_THROW(places::scoreTraversal({}), std::invalid_argument);
  EXPECT_THROW(places::scoreTraversal({outcome({0}, std::nan(""), 0)}), std::invalid_argument);
}

TEST(TraversalMetrics, SmallestKAndSeparation) {
  const std::vector<float> v = {3.0f, 1.0f, 2.0f, 1.0f, 5.0f};
  EXPECT_EQ(places::smallestK(v, 3), (std::vector<int>{1, 3, 2}));
  EXPECT_EQ(places::smallestK(v, 9).size(), 5u);
  // mean 2.4, population sd sqrt(((0.6^2) + 1.4^2 + 0.4^2 + 1.4^2 + 2.6^2) / 5) = sqrt(2.24).
  EXPECT_NEAR(places::separation(v), 1.4 / std::sqrt(2.24), 1e-6);
  EXPECT_EQ(places::separation({2.0f, 2.0f}), 0.0);
}

}  // namespace
