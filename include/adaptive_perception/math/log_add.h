#pragma once
// log(exp(a) + exp(b)) without exp or log in the inner loops of the image likelihoods: the
// correction log(1 + exp(-x)) is read from a table and interpolated linearly.
//
// Contract:
//  - log1pExpNeg(x) = log(1 + exp(-x)) for x >= 0 within kLogAddMaxError (absolute); 0 beyond
//    kLogAddTableEnd, where the true value is below 4.3e-18. A negative x is taken as 0 (its caller
//    passes |a - b|); a NaN gives NaN (and so does logAddExp with a NaN term).
//  - logAddExp(a, b) = max(a, b) + log1pExpNeg(|a - b|); -inf + x = x.
//  - The table is built when the library loads (a constant, read-only afterwards: thread-safe).
#include <array>
#include <cmath>
#include <utility>

namespace adaptive_perception::math {

inline constexpr double kLogAddTableEnd = 40.0;
inline constexpr int kLogAddStepsPerUnit = 64;
// Linear interpolation's error bound h^2 / 8 * max f'' with f'' <= 1/4 and h = 1/64.
inline constexpr double kLogAddMaxError = 1.0 / (64.0 * 64.0 * 8.0 * 4.0);

namespace detail {
inline constexpr int kLogAddTableSize = static_cast<int>(kLogAddTableEnd) * kLogAddStepsPerUnit + 2;
inline const std::array<double, kLogAddTableSize> kLogAddTable = [] {
  std::array<double, kLogAddTableSize> t{};
  for (int i = 0; i < kLogAddTableSize; ++i)
    t[i] = std::log1p(std::exp(-static_cast<double>(i) / kLogAddStepsPerUnit));
  return t;
}();
}  // namespace detail

inline double log1pExpNeg(double x) {
  if (!(x < kLogAddTableEnd)) return x >= kLogAddTableEnd ? 0.0 : x;  // NaN stays NaN
  if (x <= 0.0) return detail::kLogAddTable[0];
  const double s = x * kLogAddStepsPerUnit;
  const int i = static_cast<int>(s);
  const double f = s - i;
  return detail::kLogAddTable[i] + f * (detail::kLogAddTable[i + 1] - detail::kLogAddTable[i]);
}

inline double logAddExp(double a, double b) {
  if (a < b) std::swap(a, b);
  if (b == -INFINITY) return a;
  return a + log1pExpNeg(a - b);
}

}  // namespace adaptive_perception::math
