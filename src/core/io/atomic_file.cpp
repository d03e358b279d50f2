#include "adaptive_perception/io/atomic_file.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace adaptive_perception::io {

void writeTextFileAtomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error(path + ": cannot write (directory missing or read-only?)");
    out << text;
    out.flush();
    if (!out) {
      out.close();
      std::filesystem::remove(tmp);
      throw std::runtime_error(path + ": write failed (disk full?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp);
    throw std::runtime_error(path + ": cannot replace: " + ec.message());
  }
}

}  // namespace adaptive_perception::io
