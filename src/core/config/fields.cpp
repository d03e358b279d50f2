#include "adaptive_perception/config/fields.h"

#include <cstdio>
#include <cstdlib>

namespace adaptive_perception::config {

std::string formatValue(Kind kind, double v) {
  if (kind == Kind::kBool) return v != 0.0 ? "true" : "false";
  char buf[32];
  if (std::isfinite(v) && v == std::floor(v) && std::fabs(v) < 1e15) {
    // Whole numbers as integers; round powers of ten from 1e5 on as 1eN.
    const double k = std::fabs(v) >= 1e5 ? std::round(std::log10(std::fabs(v))) : 0.0;
    if (k > 0 && std::fabs(v) == std::pow(10.0, k)) {
      std::snprintf(buf, sizeof(buf), "%se%d", v < 0 ? "-1" : "1", static_cast<int>(k));
      return buf;
    }
    std::snprintf(buf, sizeof(buf), "%lld", static_cast<long long>(v));
    return buf;
  }
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buf, sizeof(buf), "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string Range::text() const {
  return std::string(lo_open ? "(" : "[") + formatValue(Kind::kDouble, lo) + ", " +
         formatValue(Kind::kDouble, hi) + (hi_open ? ")" : "]");
}

std::string markdownTable(const std::vector<ParameterDoc>& rows) {
  std::string out =
      "| parameter | type | default | allowed | what it does |\n|---|---|---|---|---|\n";
  for (const ParameterDoc& r : rows)
    out += "| `~" + r.name + "` | " + r.type + " | " +
           (r.default_value.empty() ? "-" : r.default_value) + " | " +
           (r.range.empty() ? "-" : r.range) + " | " + r.doc + " |\n";
  return out;
}

std::string formatList(const std::vector<std::string>& items) {
  std::string out = "[";
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out + "]";
}

std::string formatList(const std::vector<double>& numbers) {
  std::vector<std::string> items;
  for (double v : numbers) items.push_back(formatValue(Kind::kDouble, v));
  return formatList(items);
}

}  // namespace adaptive_perception::config
