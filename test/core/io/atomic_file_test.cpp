// io::writeTextFileAtomically: the target gets the whole text, nothing else in its folder changes.
#include "adaptive_perception/io/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "../scratch_dir.h"

namespace ap = adaptive_perception;
namespace fs = std::filesystem;

namespace {

std::string readAll(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class AtomicFileTest : public ::testing::Test {
 protected:
  std::size_t filesInDir() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {}));
  }
  adaptive_perception::test_support::ScratchDir scratch_{"atomic_file_test"};
  const fs::path& dir_ = scratch_.path();
};

TEST_F(AtomicFileTest, WritesAndReplacesWithNoFileLeftBehind) {
  const fs::path x = dir_ / "map.yaml";
  ap::io::writeTextFileAtomically(x.string(), "first\n");
  EXPECT_EQ(readAll(x), "first\n");
  ap::io::writeTextFileAtomically(x.string(), "second, longer\n");
  EXPECT_EQ(readAll(x), "second, longer\n");
  EXPECT_EQ(filesInDir(), 1u);
}

TEST_F(AtomicFileTest, AUsersTmpFileBesideTheTargetIsNotTouched) {
  const fs::path x = dir_ / "prior.yaml";
  std::ofstream(dir_ / "prior.yaml.tmp") << "the user's own file\n";
  ap::io::writeTextFileAtomically(x.string(), "saved\n");
  EXPECT_EQ(readAll(dir_ / "prior.yaml.tmp"), "the user's own file\n");
  EXPECT_EQ(readAll(x), "saved\n");
  EXPECT_EQ(filesInDir(), 2u);
}

TEST_F(AtomicFileTest, ATemporaryWithASuffixIsUniqueAndEndsWithIt) {
  const fs::path video = dir_ / "clip.avi";
  const std::string a = ap::io::createTemporaryBeside(video.string(), ".avi");
  const std::string b = ap::io::createTemporaryBeside(video.string(), ".avi");
  EXPECT_NE(a, b);
  for (const std::string& t : {a, b}) {
    const std::string name = fs::path(t).filename().string();
    EXPECT_EQ(name.rfind(".clip.avi.", 0), 0u) << name;
    EXPECT_EQ(name.substr(name.size() - 4), ".avi") << name;
    EXPECT_EQ(fs::file_size(t), 0u);
    EXPECT_EQ(fs::path(t).parent_path(), dir_);
  }
  EXPECT_FALSE(fs::exists(video));
  EXPECT_THROW(ap::io::createTemporaryBeside(video.string(), "/x"), std::invalid_argument);
  EXPECT_EQ(filesInDir(), 2u);
}

TEST_F(AtomicFileTest, ANameTooLongIsRefusedWithAMessageAndNothingIsWritten) {
  const fs::path x = dir_ / (std::string(300, 'm') + ".yaml");
  try {
    ap::io::writeTextFileAtomically(x.string(), "text\n");
    FAIL() << "a 305-byte file name was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("file name of 305 bytes"), std::string::npos) << e.what();
  }
  EXPECT_EQ(filesInDir(), 0u);
}

TEST_F(AtomicFileTest, ANameJustBelowTheLimitGetsAShortTemporaryName) {
  const fs::path x = dir_ / std::string(250, 'n');  // + ".XXXXXX" would pass 255 without a cut
  ap::io::writeTextFileAtomically(x.string(), "text\n");
  EXPECT_EQ(readAll(x), "text\n");
  EXPECT_EQ(filesInDir(), 1u);
}

TEST_F(AtomicFileTest, AMissingFolderIsNamedInTheError) {
  const fs::path x = dir_ / "no_such_folder" / "map.yaml";
  try {
    ap::io::writeTextFileAtomically(x.string(), "text\n");
    FAIL() << "wrote into a missing folder";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(x.string()), std::string::npos) << e.what();
  }
  EXPECT_THROW(ap::io::writeTextFileAtomically("", "text\n"), std::runtime_error);
  EXPECT_THROW(ap::io::writeTextFileAtomically(dir_.string() + "/", "text\n"), std::runtime_error);
}

TEST(AbsolutePath, RelativeNamesAreResolvedAgainstTheCurrentDirectory) {
  EXPECT_EQ(ap::io::absolutePath("a/../b.yaml"), (fs::current_path() / "b.yaml").string());
  EXPECT_EQ(ap::io::absolutePath("/x/./y"), "/x/y");
}

}  // namespace
