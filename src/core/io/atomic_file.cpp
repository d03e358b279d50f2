#include "adaptive_perception/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace adaptive_perception::io {

namespace fs = std::filesystem;

namespace {

std::runtime_error failure(const std::string& path, const std::string& what, int err) {
  return std::runtime_error(path + ": " + what + ": " + std::strerror(err));
}

// A new file of a unique name beside `path` (mkstemp), its mode the usual one under the umask;
// returns its descriptor and sets `tmp` to its name.
int temporaryBeside(const std::string& path, std::string* tmp, const std::string& suffix = "") {
  if (path.empty()) throw std::runtime_error("empty file name: nothing written");
  const fs::path target(path);
  const std::string name = target.filename().string();
  if (name.empty() || name == "." || name == "..")
    throw std::runtime_error(path + ": names a folder, not a file: nothing written");
  // A file name longer than the file system allows would fail at the rename; say so first.
  const long name_max =
      ::pathconf(target.has_parent_path() ? target.parent_path().c_str() : ".", _PC_NAME_MAX);
  if (name_max > 0 && static_cast<long>(name.size()) > name_max)
    throw std::runtime_error(path + ": file name of " + std::to_string(name.size()) +
                             " bytes; this file system allows " + std::to_string(name_max));
  // The temporary name stays short enough whatever the target's length (mkstemp adds 7 bytes).
  const std::string stem = name.substr(0, std::min<std::size_t>(name.size(), 200));
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  *tmp = (folder / ("." + stem + ".XXXXXX" + suffix)).string();
  std::vector<char> buf(tmp->begin(), tmp->end());
  buf.push_back('\0');
  const int fd = ::mkstemps(buf.data(), static_cast<int>(suffix.size()));
  if (fd < 0) throw failure(path, "cannot create a file in its folder", errno);
  tmp->assign(buf.data());
  // mkstemp makes the file 0600; a saved map or prior gets the usual mode under the umask.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  return fd;
}

}  // namespace

std::string createTemporaryBeside(const std::string& path, const std::string& suffix) {
  if (suffix.find('/') != std::string::npos || suffix.size() > 16)
    throw std::invalid_argument("createTemporaryBeside: suffix '" + suffix +
                                "' (allowed: at most 16 bytes, no '/')");
  std::string tmp;
  const int fd = temporaryBeside(path, &tmp, suffix);
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw failure(path, "cannot close a new file in its folder", err);
  }
  return tmp;
}

void writeTextFileAtomically(const std::string& path, const std::string& text) {
  std::string tmp;
  const int fd = temporaryBeside(path, &tmp);
  const fs::path folder =
      fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
  auto abandon = [&](const std::string& what, int err) {
    ::close(fd);
    ::unlink(tmp.c_str());
    return failure(path, what, err);
  };
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw abandon("write failed (disk full?)", n < 0 ? errno : EIO);
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) throw abandon("cannot flush to disk", errno);
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw failure(path, "cannot close", err);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw failure(path, "cannot replace", err);
  }
  const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (dir >= 0) {  // the rename itself reaches the disk (best effort: not every file system can)
    ::fsync(dir);
    ::close(dir);
  }
}

std::string absolutePath(const std::string& path) {
  std::error_code ec;
  const fs::path a = fs::absolute(path, ec);
  return ec ? path : a.lexically_normal().string();
}

}  // namespace adaptive_perception::io
