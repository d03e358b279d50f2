#include "adaptive_perception/io/image_list.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "adaptive_perception/io/image_folder.h"

namespace adaptive_perception::io {
std::vector<LabelledPath> readImageList(const std::string& csv_path) {
  std::ifstream in(csv_path);
  if (!in) throw std::runtime_error(csv_path + ": cannot open image list");
  const std::filesystem::path dir = std::filesystem::path(csv_path).parent_path();
  std::vector<LabelledPath> out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    const std::string t = trimmed(line);
    if (t.empty() || t[0] == '#') continue;
    if (n == 1 && t.rfind("image_path", 0) == 0) continue;
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
    const std::filesystem::path fp(path);
    p.path = fp.is_absolute() ? path : (dir / fp).string();
    p.line = n;
    out.push_back(p);
  }
  return out;
}

}  // namespace adaptive_perception::io
