#include "adaptive_perception/places/histogram_distance.h"

#include <algorithm>
#include <array>
#include <cmath>
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

}  // namespace adaptive_perception::places
