// io::readTraversal and io::readFrameCorrespondences on folders and lists made here, with the
// quirks real benchmarks have (numbers without padding, other files, headers, bad lines).
#include "adaptive_perception/io/image_folder.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "../scratch_dir.h"

namespace ap = adaptive_perception;
namespace fs = std::filesystem;

namespace {

class ImageFolderTest : public ::testing::Test {
 protected:
  void write(const fs::path& p, const std::string& text) const {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
  }
  std::string errorOf(const std::string& csv) const {
    try {
      ap::io::readFrameCorrespondences(csv);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
  adaptive_perception::test_support::ScratchDir scratch_{"image_folder"};
  const fs::path& dir_ = scratch_.path();
};

TEST(NaturalOrder, ComparesDigitRunsByValue) {
  EXPECT_TRUE(ap::io::naturalLess("9.jpg", "10.jpg"));
  EXPECT_FALSE(ap::io::naturalLess("10.jpg", "9.jpg"));
  EXPECT_TRUE(ap::io::naturalLess("images-00010.png", "images-00020.png"));
  EXPECT_TRUE(ap::io::naturalLess("a2", "b1"));
  EXPECT_FALSE(ap::io::naturalLess("x1", "x1"));
}

TEST_F(ImageFolderTest, FolderInNameOrderWithOtherFilesSkipped) {
  for (const char* n : {"10.jpg", "9.JPG", "0.png", "Thumbs.db", "README.md"})
    write(dir_ / "ref" / n, "x");
  int skipped = -1;
  const auto files = ap::io::listImages((dir_ / "ref").string(), &skipped);
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(fs::path(files[0]).filename(), "0.png");
  EXPECT_EQ(fs::path(files[1]).filename(), "9.JPG");
  EXPECT_EQ(fs::path(files[2]).filename(), "10.jpg");
  EXPECT_EQ(skipped, 2);
  EXPECT_EQ(ap::io::readTraversal((dir_ / "ref").string()), files);
}

TEST_F(ImageFolderTest, CsvListKeepsItsOrderAndResolvesRelativePaths) {
  write(dir_ / "list.csv", "image_path,extra\n# a comment\nb.png,1\n\n/abs/a.png\nsub/c.jpg , x\n");
  const auto files = ap::io::readTraversal((dir_ / "list.csv").string());
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0], (dir_ / "b.png").string());
  EXPECT_EQ(files[1], "/abs/a.png");
  EXPECT_EQ(files[2], (dir_ / "sub/c.jpg").string());
}

TEST_F(ImageFolderTest, CsvLinesAreNumberedTrimmedAndWithoutCommentsOrBlanks) {
  const fs::path csv = dir_ / "lines.csv";
  write(csv, "# comment\r\n  a,1 \r\n\n\t\nb\n");
  const std::vector<ap::io::CsvLine> lines = ap::io::readCsvLines(csv.string(), "cannot open it");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].number, 2);
  EXPECT_EQ(lines[0].text, "a,1");
  EXPECT_EQ(lines[1].number, 5);
  EXPECT_EQ(lines[1].text, "b");
  try {
    ap::io::readCsvLines((dir_ / "none.csv").string(), "cannot open it");
    ADD_FAILURE() << "a missing file was read";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "none.csv").string() + ": cannot open it");
  }
  EXPECT_EQ(ap::io::besideList("/data/lists/l.csv", "img/a.png"), "/data/lists/img/a.png");
  EXPECT_EQ(ap::io::besideList("/data/lists/l.csv", "/abs/a.png"), "/abs/a.png");
  EXPECT_EQ(ap::io::besideList("l.csv", "a.png"), "a.png");
}

TEST_F(ImageFolderTest, EmptyOrMissingTraversalsAreNamed) {
  fs::create_directories(dir_ / "empty");
  write(dir_ / "empty" / "notes.txt", "x");
  EXPECT_THROW(ap::io::readTraversal((dir_ / "empty").string()), std::runtime_error);
  EXPECT_THROW(ap::io::readTraversal((dir_ / "missing").string()), std::runtime_error);
  write(dir_ / "blank.csv", "# nothing\n\n");
  EXPECT_THROW(ap::io::readTraversal((dir_ / "blank.csv").string()), std::runtime_error);
}

TEST_F(ImageFolderTest, CorrespondencesCountFromOneInTheFile) {
  write(dir_ / "gt.csv", "query_idx,ref_idx,tolerance\n1,1,15\n2,5,0\n");
  const auto c = ap::io::readFrameCorrespondences((dir_ / "gt.csv").string());
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].query, 0);
  EXPECT_EQ(c[0].reference, 0);
  EXPECT_EQ(c[0].tolerance, 15);
  EXPECT_EQ(c[1].query, 1);
  EXPECT_EQ(c[1].reference, 4);
  EXPECT_EQ(c[1].tolerance, 0);
}

TEST_F(ImageFolderTest, BadCorrespondenceLinesNameFileAndLine) {
  const std::string csv = (dir_ / "gt.csv").string();
  write(csv, "1,1,1\n2,x,1\n");
  EXPECT_NE(errorOf(csv).find("gt.csv:2:"), std::string::npos) << errorOf(csv);
  write(csv, "1,1,1\n0,1,1\n");
  EXPECT_NE(errorOf(csv).find("gt.csv:2: indices count from 1"), std::string::npos);
  write(csv, "1,1,-1\n");
  EXPECT_NE(errorOf(csv).find("gt.csv:1: negative tolerance"), std::string::npos);
  write(csv, "1,1\n");
  EXPECT_NE(errorOf(csv).find("gt.csv:1:"), std::string::npos);
  write(csv, "1,1,1\nquery,ref,tol\n");  // a header after data is a bad line
  EXPECT_NE(errorOf(csv).find("gt.csv:2:"), std::string::npos);
  write(csv, "query,ref,tol\n");
  EXPECT_NE(errorOf(csv).find("no correspondence"), std::string::npos);
  EXPECT_NE(errorOf((dir_ / "none.csv").string()).find("cannot open"), std::string::npos);
}

}  // namespace
