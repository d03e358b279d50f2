#include "adaptive_perception/io/image_folder.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace adaptive_perception::io {

namespace fs = std::filesystem;

namespace {
bool parseInt(const std::string& text, long* out) {
  const std::string t = trimmed(text);
  if (t.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(t.c_str(), &end, 10);
  if (*end != '\0' || errno == ERANGE || v < -1000000000L || v > 1000000000L) return false;
  *out = v;
  return true;
}
}  // namespace

std::vector<CsvLine> readCsvLines(const std::string& path, const std::string& cannot_open) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": " + cannot_open);
  std::vector<CsvLine> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::string t = trimmed(line);
    if (!t.empty() && t[0] != '#') out.push_back({n, std::move(t)});
  }
  return out;
}

std::string besideList(const std::string& list_path, const std::string& path) {
  const fs::path p(path);
  return p.is_absolute() ? path : (fs::path(list_path).parent_path() / p).string();
}

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

bool isImageFile(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".jpg" || ext == ".jpeg" || ext == ".png" || ext == ".bmp" || ext == ".ppm" ||
         ext == ".pgm";
}

bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) &&
        std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t i2 = i, j2 = j;
      while (i2 < a.size() && std::isdigit(static_cast<unsigned char>(a[i2]))) ++i2;
      while (j2 < b.size() && std::isdigit(static_cast<unsigned char>(b[j2]))) ++j2;
      const std::string da = a.substr(i, i2 - i), db = b.substr(j, j2 - j);
      const std::size_t za = da.find_first_not_of('0'), zb = db.find_first_not_of('0');
      const std::string va = za == std::string::npos ? "" : da.substr(za);
      const std::string vb = zb == std::string::npos ? "" : db.substr(zb);
      if (va.size() != vb.size()) return va.size() < vb.size();
      if (va != vb) return va < vb;
      i = i2;
      j = j2;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

std::vector<std::string> listImages(const std::string& dir, int* skipped) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw std::runtime_error(dir + ": no such folder");
  std::vector<std::string> names;
  int other = 0;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file(ec)) continue;
    if (isImageFile(e.path().string()))
      names.push_back(e.path().filename().string());
    else
      ++other;
  }
  if (ec) throw std::runtime_error(dir + ": cannot list the folder: " + ec.message());
  std::sort(names.begin(), names.end(), naturalLess);
  std::vector<std::string> out;
  out.reserve(names.size());
  for (const auto& n : names) out.push_back((fs::path(dir) / n).string());
  if (skipped) *skipped = other;
  return out;
}

std::vector<std::string> readTraversal(const std::string& folder_or_csv) {
  std::error_code ec;
  std::vector<std::string> out;
  if (fs::is_directory(folder_or_csv, ec)) {
    out = listImages(folder_or_csv);
    if (out.empty())
      throw std::runtime_error(folder_or_csv + ": no image (jpg, png, bmp, ppm, pgm) in the folder");
    return out;
  }
  for (const CsvLine& l : readCsvLines(folder_or_csv, "no such folder or image list")) {
    if (out.empty() && l.text.rfind("image_path", 0) == 0) continue;  // a header
    const std::string path = trimmed(l.text.substr(0, l.text.find(',')));
    if (path.empty())
      throw std::runtime_error(folder_or_csv + ":" + std::to_string(l.number) +
                               ": empty image path");
    out.push_back(besideList(folder_or_csv, path));
  }
  if (out.empty()) throw std::runtime_error(folder_or_csv + ": the image list names no image");
  return out;
}

std::vector<FrameCorrespondence> readFrameCorrespondences(const std::string& csv_path) {
  std::vector<FrameCorrespondence> out;
  bool data_seen = false;
  for (const CsvLine& l : readCsvLines(csv_path, "cannot open the ground-truth file")) {
    const std::string& t = l.text;
    std::vector<std::string> fields;
    std::stringstream ss(t);
    std::string f;
    while (std::getline(ss, f, ',')) fields.push_back(f);
    const std::string where = csv_path + ":" + std::to_string(l.number) + ": ";
    long v[3];
    const bool numeric = fields.size() == 3 && parseInt(fields[0], &v[0]) &&
                         parseInt(fields[1], &v[1]) && parseInt(fields[2], &v[2]);
    if (!numeric) {
      const bool header = !data_seen && !t.empty() && std::isalpha(static_cast<unsigned char>(t[0]));
      if (header) continue;
      throw std::runtime_error(where + "expected `query_index,reference_index,tolerance` (integers), got '" +
                               t + "'");
    }
    data_seen = true;
    if (v[0] < 1 || v[1] < 1)
      throw std::runtime_error(where + "indices count from 1, got '" + t + "'");
    if (v[2] < 0) throw std::runtime_error(where + "negative tolerance in '" + t + "'");
    out.push_back({static_cast<int>(v[0] - 1), static_cast<int>(v[1] - 1), static_cast<int>(v[2])});
  }
  if (out.empty()) throw std::runtime_error(csv_path + ": no correspondence line");
  return out;
}

}  // namespace adaptive_perception::io
