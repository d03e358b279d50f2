// The CSV image-list reader: header, comments, relative paths, and errors with line numbers.
#include "adaptive_perception/io/image_list.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../scratch_dir.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;

TEST(ImageList, ReadsRelativeAndAbsolutePaths) {
  const adaptive_perception::test_support::ScratchDir scratch("ap_list");
  const fs::path& dir = scratch.path();
  const std::string csv = (dir / "images.csv").string();
  std::ofstream(csv)
      << "image_path,place\n# a comment\n\na.png,kitchen\n /abs/b.png , corridor \r\n";
  const auto list = io::readImageList(csv);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].path, (dir / "a.png").string());
  EXPECT_EQ(list[0].label, "kitchen");
  EXPECT_EQ(list[0].line, 4);
  EXPECT_EQ(list[1].path, "/abs/b.png");
  EXPECT_EQ(list[1].label, "corridor");

  std::ofstream(csv) << "a.png,kitchen\nb.png\n";
  try {
    io::readImageList(csv);
    FAIL() << "a line without a label was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("images.csv:2"), std::string::npos) << e.what();
  }
  std::ofstream(csv) << "a.png,\n";
  EXPECT_THROW(io::readImageList(csv), std::runtime_error);
  EXPECT_THROW(io::readImageList((dir / "missing.csv").string()), std::runtime_error);
}
