#pragma once
// Distances between band histograms (papers/004 section 4, and eq. 28 of papers/001). H is the
// test image's histogram, K the training image's; each band sums to 1. All return 0 for identical
// histograms and grow with the difference.
#include <string>
#include <vector>

namespace adaptive_perception::places {

enum class Distance {
  // eq. (2): sum (h - k)^2 / k. Empty bins: a bin empty in both contributes 0; a bin empty in K
  // but not in H uses h as the denominator (contributes h), so the distance stays finite and
  // a colour the training image never showed costs its whole mass. Not symmetric.
  kChiSquare = 0,
  // eq. (3): sum h log2(2h / (h + k)) + k log2(2k / (h + k)); 0 log 0 = 0. Symmetric, at most 2.
  kJeffrey = 1,
  // eq. (4) as the paper writes it: max over bins of |h - k| (bin-wise, not cumulative).
  kKolmogorovSmirnov = 2,
  // The textbook Kolmogorov-Smirnov statistic: max over bins of |cum(h) - cum(k)|.
  kKsCumulative = 3,
  // Swain and Ballard's intersection, eq. (28) of papers/001, as a distance: 1 - sum min(h, k) /
  // sum h.
  kIntersection = 4,
};
constexpr int kNumDistances = 5;

std::string distanceName(Distance d);  // chi_square, jeffrey, ks, ks_cumulative, intersection
/// Throws std::invalid_argument listing the valid names.
Distance distanceFromName(const std::string& name);
/// "all", "paper" (chi_square, jeffrey, ks) or a comma-separated list of names.
std::vector<Distance> parseDistances(const std::string& list);
std::string distancesToString(const std::vector<Distance>& ds);

/// The distance between two band histograms of `bins` entries.
double bandDistance(Distance d, const float* h, const float* k, int bins);
/// The mean over the three bands of 3 * bins floats (the band average, "3" in eq. 5).
double histogramDistance(Distance d, const float* h, const float* k, int bins);

}  // namespace adaptive_perception::places
