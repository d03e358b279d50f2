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

/// histogramDistance of one test histogram H against many training rows K, the fast way: single
/// precision, four bins at a time (OpenCV's universal intrinsics), with the terms that depend on
/// H alone computed once. It agrees with histogramDistance to about 1e-6 of the distance's range
/// (the unit test checks 1e-5 on random histograms, with empty bins).
///   Jeffrey      rewritten as m + h log2 h + k log2 k - m log2 m per bin (m = h + k): one
///                logarithm per bin (a four-lane series, exact to float precision), with the
///                training row's terms given by storedTerms() (computed once when it is stored);
///   ks_cumulative  the running sums of H once, those of K four bins at a time.
/// H (3 * bins floats) must outlive the object.
class HistogramQuery {
 public:
  HistogramQuery(Distance d, const float* h, int bins);
  /// The terms of a training row that Jeffrey needs (sum of k + k log2 k over the row; 0 for the
  /// other distances' use): store it beside the row.
  static double storedTerms(const float* k, int bins);
  /// d(H, K) / 3 summed over the bands, as histogramDistance; `k_terms` is storedTerms(k) (read by
  /// Jeffrey only).
  double operator()(const float* k, double k_terms) const;

 private:
  Distance d_;
  const float* h_;
  int bins_;
  double h_terms_ = 0.0;             // Jeffrey: storedTerms(h)
  std::vector<float> h_cumulative_;  // ks_cumulative: running sums per band
};

}  // namespace adaptive_perception::places
