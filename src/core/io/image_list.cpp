#include "adaptive_perception/io/image_list.h"

#include <stdexcept>

#include "adaptive_perception/io/image_folder.h"

namespace adaptive_perception::io {
std::vector<LabelledPath> readImageList(const std::string& csv_path) {
  std::vector<LabelledPath> out;
  for (const CsvLine& l : readCsvLines(csv_path, "cannot open image list")) {
    const std::string& t = l.text;
    const int n = l.number;
    if (out.empty() && t.rfind("image_path", 0) == 0) continue;  // a header
    const auto comma = t.find(',');
    if (comma == std::string::npos)
      throw std::runtime_error(csv_path + ":" + std::to_string(n) +
                               ": expected `image_path,label`, got '" + t + "'");
    LabelledPath p;
    const std::string path = trimmed(t.substr(0, comma));
    p.label = trimmed(t.substr(comma + 1));
    if (path.empty() || p.label.empty())
      throw std::runtime_error(csv_path + ":" + std::to_string(n) + ": empty path or label");
    if (p.label.find(',') != std::string::npos)
      throw std::runtime_error(csv_path + ":" + std::to_string(n) + ": more than two columns");
    p.path = besideList(csv_path, path);
    p.line = n;
    out.push_back(p);
  }
  return out;
}

}  // namespace adaptive_perception::io
