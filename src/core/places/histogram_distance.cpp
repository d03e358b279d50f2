#include "adaptive_perception/places/histogram_distance.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <opencv2/core/hal/intrin.hpp>
#include <sstream>
#include <stdexcept>

namespace adaptive_perception::places {
namespace {

const std::array<const char*, kNumDistances> kNames = {"chi_square", "jeffrey", "ks",
                                                       "ks_cumulative", "intersection"};

double chiSquare(const float* h, const float* k, int bins) {
  double s = 0.0;
  for (int i = 0; i < bins; ++i) {
    const double d = h[i] - k[i];
    if (k[i] > 0.0f)
      s += d * d / k[i];
    else
      s += h[i];  // empty in K: (h - 0)^2 / h
  }
  return s;
}

double jeffrey(const float* h, const float* k, int bins) {
  double s = 0.0;
  for (int i = 0; i < bins; ++i) {
    const double a = h[i], b = k[i], m = a + b;
    if (a > 0.0) s += a * std::log2(2.0 * a / m);
    if (b > 0.0) s += b * std::log2(2.0 * b / m);
  }
  return s;
}

double ksBinwise(const float* h, const float* k, int bins) {
  double m = 0.0;
  for (int i = 0; i < bins; ++i) m = std::max(m, static_cast<double>(std::abs(h[i] - k[i])));
  return m;
}

double ksCumulative(const float* h, const float* k, int bins) {
  double ch = 0.0, ck = 0.0, m = 0.0;
  for (int i = 0; i < bins; ++i) {
    ch += h[i];
    ck += k[i];
    m = std::max(m, std::abs(ch - ck));
  }
  return m;
}

double intersection(const float* h, const float* k, int bins) {
  double num = 0.0, den = 0.0;
  for (int i = 0; i < bins; ++i) {
    num += std::min(h[i], k[i]);
    den += h[i];
  }
  return den > 0.0 ? 1.0 - num / den : 1.0;
}

}  // namespace

std::string distanceName(Distance d) {
  const int i = static_cast<int>(d);
  if (i < 0 || i >= kNumDistances) throw std::invalid_argument("bad distance index");
  return kNames[i];
}

Distance distanceFromName(const std::string& name) {
  for (int i = 0; i < kNumDistances; ++i)
    if (name == kNames[i]) return static_cast<Distance>(i);
  std::string valid;
  for (const char* n : kNames) valid += std::string(valid.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown distance '" + name + "' (valid: " + valid + ")");
}

std::vector<Distance> parseDistances(const std::string& list) {
  if (list == "paper")
    return {Distance::kChiSquare, Distance::kJeffrey, Distance::kKolmogorovSmirnov};
  std::vector<Distance> out;
  if (list == "all") {
    for (int i = 0; i < kNumDistances; ++i) out.push_back(static_cast<Distance>(i));
    return out;
  }
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) {
      const Distance d = distanceFromName(item);
      if (std::find(out.begin(), out.end(), d) == out.end()) out.push_back(d);
    }
  if (out.empty()) throw std::invalid_argument("empty distance list");
  return out;
}

std::string distancesToString(const std::vector<Distance>& ds) {
  std::string s;
  for (Distance d : ds) s += (s.empty() ? "" : ",") + distanceName(d);
  return s;
}

double bandDistance(Distance d, const float* h, const float* k, int bins) {
  switch (d) {
    case Distance::kChiSquare:
      return chiSquare(h, k, bins);
    case Distance::kJeffrey:
      return jeffrey(h, k, bins);
    case Distance::kKolmogorovSmirnov:
      return ksBinwise(h, k, bins);
    case Distance::kKsCumulative:
      return ksCumulative(h, k, bins);
    case Distance::kIntersection:
      return intersection(h, k, bins);
  }
  throw std::invalid_argument("bad distance");
}

double histogramDistance(Distance d, const float* h, const float* k, int bins) {
  double s = 0.0;
  for (int band = 0; band < 3; ++band) s += bandDistance(d, h + band * bins, k + band * bins, bins);
  return s / 3.0;
}

// ---- HistogramQuery: the same distances, four bins at a time ----------------------------------
namespace {

using cv::v_float32x4;

// sum over [0, n) of f(h, k), f a lane-wise functor; the tail (n not a multiple of 4) in scalars
// through the same functor on one-lane vectors.
template <typename F>
float simdSum(const float* h, const float* k, int n, F f) {
  v_float32x4 acc = cv::v_setzero_f32();
  int i = 0;
  for (; i + 4 <= n; i += 4) acc += f(cv::v_load(h + i), cv::v_load(k + i));
  float s = cv::v_reduce_sum(acc);
  for (; i < n; ++i) s += cv::v_reduce_sum(f(cv::v_setall_f32(h[i]), cv::v_setall_f32(k[i]))) / 4;
  return s;
}

template <typename F>
float simdMax(const float* h, const float* k, int n, F f) {
  v_float32x4 acc = cv::v_setzero_f32();
  int i = 0;
  for (; i + 4 <= n; i += 4) acc = cv::v_max(acc, f(cv::v_load(h + i), cv::v_load(k + i)));
  float m = cv::v_reduce_max(acc);
  for (; i < n; ++i)
    m = std::max(m, cv::v_reduce_max(f(cv::v_setall_f32(h[i]), cv::v_setall_f32(k[i]))));
  return m;
}

// Running sums of four lanes: (a, b, c, d) -> (a, a + b, a + b + c, a + b + c + d).
inline v_float32x4 prefixSum(v_float32x4 x) {
  x += cv::v_rotate_left<1>(x);  // v_rotate_left shifts towards the higher lanes, filling zeros
  x += cv::v_rotate_left<2>(x);
  return x;
}

// log2 of four positive normal floats: x = 2^e (1 + f), f in [0, 1), and log2(1 + f) = f P(f)
// with P the least-squares polynomial of degree 5 on Chebyshev nodes of [0, 1]: error 2.5e-6,
// so a distance (sum of m log2 m over bins whose m sum to 2 per band) is off by at most 5e-6.
inline v_float32x4 log2Lanes(v_float32x4 x) {
  const cv::v_int32x4 bits = cv::v_reinterpret_as_s32(x);
  const cv::v_int32x4 e = cv::v_shr<23>(bits) - cv::v_setall_s32(127);
  const v_float32x4 f = cv::v_reinterpret_as_f32((bits & cv::v_setall_s32(0x007fffff)) |
                                                 cv::v_setall_s32(0x3f800000)) -
                        cv::v_setall_f32(1.0f);
  static constexpr float c[6] = {1.442534767e+00f,  -7.180333966e-01f, 4.571571246e-01f,
                                 -2.773394316e-01f, 1.214707340e-01f,  -2.579152741e-02f};
  // Estrin's scheme: a short dependency chain, so that successive bins overlap in the pipeline
  const v_float32x4 f2 = f * f, f4 = f2 * f2;
  auto pair = [&](int j) {
    return cv::v_muladd(cv::v_setall_f32(c[j + 1]), f, cv::v_setall_f32(c[j]));
  };
  const v_float32x4 p = cv::v_muladd(pair(4), f4, cv::v_muladd(pair(2), f2, pair(0)));
  return cv::v_cvt_f32(e) + p * f;
}

inline v_float32x4 broadcastLast(v_float32x4 x) { return cv::v_broadcast_element<3>(x); }

}  // namespace

HistogramQuery::HistogramQuery(Distance d, const float* h, int bins) : d_(d), h_(h), bins_(bins) {
  if (bins < 1) throw std::invalid_argument("HistogramQuery: bins must be >= 1");
  if (d == Distance::kJeffrey) {
    h_terms_ = storedTerms(h, bins);
  } else if (d == Distance::kKsCumulative) {
    h_cumulative_.resize(3 * static_cast<size_t>(bins));
    for (int band = 0; band < 3; ++band) {
      float c = 0.0f;
      for (int i = band * bins; i < (band + 1) * bins; ++i) h_cumulative_[i] = (c += h[i]);
    }
  }
}

double HistogramQuery::storedTerms(const float* k, int bins) {
  double s = 0.0;
  for (int i = 0; i < 3 * bins; ++i)
    if (k[i] > 0.0f) s += k[i] + static_cast<double>(k[i]) * std::log2(static_cast<double>(k[i]));
  return s;
}

double HistogramQuery::operator()(const float* k, double k_terms) const {
  const int n = 3 * bins_;
  const v_float32x4 zero = cv::v_setzero_f32();
  switch (d_) {
    case Distance::kChiSquare:
      // (h - k)^2 / k where k > 0, else h (the documented empty-bin rule).
      return simdSum(h_, k, n,
                     [&](v_float32x4 h, v_float32x4 kk) {
                       const v_float32x4 d = h - kk;
                       const v_float32x4 safe = cv::v_max(kk, cv::v_setall_f32(FLT_MIN));
                       return cv::v_select(kk > zero, d * d / safe, h);
                     }) /
             3.0;
    case Distance::kJeffrey: {
      // sum m log2 m, m = h + k. Bins empty on both sides add 0 (0 log 0 = 0) and are skipped
      // four at a time, so a sparse histogram costs its occupied bins.
      const v_float32x4 tiny = cv::v_setall_f32(FLT_MIN);
      auto term = [&](v_float32x4 m) {
        return cv::v_select(m > zero, m * log2Lanes(cv::v_max(m, tiny)), zero);
      };
      v_float32x4 acc0 = zero, acc1 = zero;  // two chains, eight bins per step
      int i = 0;
      for (; i + 8 <= n; i += 8) {
        const v_float32x4 m0 = cv::v_load(h_ + i) + cv::v_load(k + i);
        const v_float32x4 m1 = cv::v_load(h_ + i + 4) + cv::v_load(k + i + 4);
        if (!cv::v_check_any(cv::v_max(m0, m1) > zero)) continue;
        acc0 += term(m0);
        acc1 += term(m1);
      }
      for (; i + 4 <= n; i += 4) acc0 += term(cv::v_load(h_ + i) + cv::v_load(k + i));
      const v_float32x4 acc = acc0 + acc1;
      double s = cv::v_reduce_sum(acc);
      for (; i < n; ++i) {
        const float m = h_[i] + k[i];
        if (m > 0.0f) s += m * std::log2(m);
      }
      return (h_terms_ + k_terms - s) / 3.0;
    }
    case Distance::kKolmogorovSmirnov:
    case Distance::kIntersection:
    case Distance::kKsCumulative: {
      double total = 0.0;
      for (int band = 0; band < 3; ++band) {
        const float* hb = h_ + band * bins_;
        const float* kb = k + band * bins_;
        if (d_ == Distance::kKolmogorovSmirnov) {
          total += simdMax(hb, kb, bins_,
                           [](v_float32x4 h, v_float32x4 kk) { return cv::v_abs(h - kk); });
        } else if (d_ == Distance::kIntersection) {
          const float num = simdSum(hb, kb, bins_,
                                    [](v_float32x4 h, v_float32x4 kk) { return cv::v_min(h, kk); });
          const float den = simdSum(hb, kb, bins_, [](v_float32x4 h, v_float32x4) { return h; });
          total += den > 0.0f ? 1.0 - num / den : 1.0;
        } else {
          const float* ch = h_cumulative_.data() + band * bins_;
          v_float32x4 carry = zero, acc = zero;
          int i = 0;
          for (; i + 4 <= bins_; i += 4) {
            const v_float32x4 ck = prefixSum(cv::v_load(kb + i)) + carry;
            carry = broadcastLast(ck);
            acc = cv::v_max(acc, cv::v_abs(cv::v_load(ch + i) - ck));
          }
          float m = cv::v_reduce_max(acc), c = cv::v_extract_n<3>(carry);
          for (; i < bins_; ++i) m = std::max(m, std::abs(ch[i] - (c += kb[i])));
          total += m;
        }
      }
      return total / 3.0;
    }
  }
  throw std::invalid_argument("bad distance");
}

}  // namespace adaptive_perception::places
