#pragma once
// A fresh, empty folder for the running test, removed with the object. It lies under the system's
// temporary folder and is named by a prefix, the process and the test, so that two tests never
// share one (ctest -j runs the test programs side by side).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <system_error>

namespace adaptive_perception::test_support {

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& prefix)
      : path_(std::filesystem::temp_directory_path() /
              (prefix + "_" + std::to_string(::getpid()) + "_" + testName())) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// path() / name as a string, for the APIs that take one.
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  static std::string testName() {
    const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
    if (!t) return "suite";
    std::string name = std::string(t->test_suite_name()) + "." + t->name();
    std::replace(name.begin(), name.end(), '/', '_');  // parametrized tests
    return name;
  }
  std::filesystem::path path_;
};

}  // namespace adaptive_perception::test_support
