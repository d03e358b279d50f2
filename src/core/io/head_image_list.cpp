#include "adaptive_perception/io/head_image_list.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "adaptive_perception/io/image_folder.h"

namespace adaptive_perception::io {

namespace {

std::vector<std::string> columns(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string c;
  while (std::getline(ss, c, ',')) out.push_back(trimmed(c));
  if (!text.empty() && text.back() == ',') out.emplace_back();
  return out;
}

double number(const std::string& text, const std::string& where, const std::string& column) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw std::runtime_error(where + column + " '" + text + "' is not a finite number");
  return v;
}

}  // namespace

std::vector<HeadImage> readHeadImageList(const std::string& csv_path) {
  const std::vector<std::string> full = {"image", "head_pitch_rad", "head_yaw_rad", "x_m",
                                         "y_m",   "torso_pitch_rad"};
  const auto joined = [&](std::size_t n) {
    std::string t;
    for (std::size_t i = 0; i < n; ++i) t += (i ? "," : "") + full[i];
    return t;
  };
  std::vector<HeadImage> out;
  std::size_t width = 0;  // columns in the header: 3, 5 or 6
  for (const CsvLine& l : readCsvLines(csv_path, "cannot open image list")) {
    const std::string where = csv_path + ":" + std::to_string(l.number) + ": ";
    const std::vector<std::string> c = columns(l.text);
    if (width == 0) {
      const bool known = (c.size() == 3 || c.size() == 5 || c.size() == 6) &&
                         std::equal(c.begin(), c.end(), full.begin());
      if (!known)
        throw std::runtime_error(where + "expected the header `" + joined(3) + "`, `" + joined(5) +
                                 "` or `" + joined(6) + "`, got '" + l.text + "'");
      width = c.size();
      continue;
    }
    if (c.size() != width)
      throw std::runtime_error(where + "expected " + std::to_string(width) + " columns (" +
                               joined(width) + "), got " + std::to_string(c.size()) + ": '" +
                               l.text + "'");
    if (c[0].empty()) throw std::runtime_error(where + "the image column is empty");
    HeadImage h;
    h.path = besideList(csv_path, c[0]);
    h.head_pitch_rad = number(c[1], where, "head_pitch_rad");
    h.head_yaw_rad = number(c[2], where, "head_yaw_rad");
    if (width >= 5 && (!c[3].empty() || !c[4].empty())) {
      if (c[3].empty() || c[4].empty())
        throw std::runtime_error(where + "x_m and y_m are given together or not at all");
      h.truth_xy_m = Eigen::Vector2d(number(c[3], where, "x_m"), number(c[4], where, "y_m"));
    }
    if (width == 6 && !c[5].empty()) h.torso_pitch_rad = number(c[5], where, "torso_pitch_rad");
    h.line = l.number;
    out.push_back(h);
  }
  if (width == 0) throw std::runtime_error(csv_path + ": empty (no header)");
  return out;
}

}  // namespace adaptive_perception::io
