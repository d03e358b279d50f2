#include "adaptive_perception/io/image_list.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace adaptive_perception::io {
namespace {
std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}
}  // namespace

std::vector<LabelledPath> readImageList(const std::string& csv_path) {
  std::ifstream in(csv_path);
  if (!in) throw std::runtime_error(csv_path + ": cannot open image list");
  const std::filesystem::path dir = std::filesystem::path(csv_path).parent_path();
  std::vector<LabelledPath> out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    if (n == 1 && t.rfind("image_path", 0) == 0) continue;
    const auto comma = t.find(',');
    if (comma == std::string::npos)
      throw std::runtime_error(csv_path + ":" + std::to_string(n) +
                               ": expected `image_path,label`, got '" + t + "'");
    LabelledPath p;
    const std::string path = trim(t.substr(0, comma));
    p.label = trim(t.substr(comma + 1));
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
