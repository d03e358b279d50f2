// io::readBenchmarkSequence on OTB- and VOT-style folders made here, with the quirks the real ones
// have (numbering from 0300, tabs, 8-value polygons, NaN boxes, Thumbs.db, lengths that differ).
#include "adaptive_perception/io/benchmark_sequence.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>

#include "../scratch_dir.h"

namespace ap = adaptive_perception;
namespace fs = std::filesystem;

namespace {

class BenchmarkSequenceTest : public ::testing::Test {
 protected:
  void image(const fs::path& p) const {
    fs::create_directories(p.parent_path());
    cv::imwrite(p.string(), cv::Mat(8, 8, CV_8UC3, cv::Scalar(10, 20, 30)));
  }
  void text(const fs::path& p, const std::string& s) const { std::ofstream(p) << s; }
  adaptive_perception::test_support::ScratchDir scratch_{"benchmark_sequence"};
  const fs::path& dir_ = scratch_.path();
};

TEST_F(BenchmarkSequenceTest, OtbFolderFromFrame0300WithTabsAndAThumbsDb) {
  const fs::path seq = dir_ / "David";
  for (int i : {300, 301, 302, 1000}) image(seq / "img" / (std::to_string(i) + ".png"));
  text(seq / "img" / "Thumbs.db", "not an image");
  text(seq / "groundtruth_rect.txt",
       "11\t21\t30\t40\n12,22,30,40\n13 23 30 40\n14, 24, 30, 40\n\n");
  const ap::io::BenchmarkSequence s = ap::io::readBenchmarkSequence(seq.string());
  EXPECT_EQ(s.name, "David");
  EXPECT_EQ(s.format, "otb");
  ASSERT_EQ(s.frames.size(), 4u);
  EXPECT_EQ(fs::path(s.frames[0]).filename(), "300.png");
  EXPECT_EQ(fs::path(s.frames[3]).filename(), "1000.png");  // natural order, not "1000" < "300"
  ASSERT_EQ(s.truth.size(), 4u);
  ASSERT_TRUE(s.truth[0]);
  EXPECT_EQ(*s.truth[0], cv::Rect2d(10, 20, 30, 40));  // 1-based to 0-based
  EXPECT_EQ(*s.truth[3], cv::Rect2d(13, 23, 30, 40));
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_NE(s.notes[0].find("not images skipped"), std::string::npos) << s.notes[0];
}

TEST_F(BenchmarkSequenceTest, VotPolygonsNanBoxesAndAShortFile) {
  const fs::path seq = dir_ / "ball1";
  for (int i = 1; i <= 4; ++i) image(seq / "imgs" / cv::format("%08d.jpg", i));
  text(seq / "groundtruth.txt",
       "10,20,40,20,40,60,10,60\n"  // axis-aligned rectangle as a polygon
       "20,10,30,20,20,30,10,20\n"  // a diamond: its bounding box
       "nan,nan,nan,nan\n");        // target out of view; the 4th frame has no line
  const ap::io::BenchmarkSequence s = ap::io::readBenchmarkSequence(seq.string() + "/");
  EXPECT_EQ(s.name, "ball1");
  EXPECT_EQ(s.format, "vot");
  ASSERT_EQ(s.truth.size(), 4u);
  EXPECT_EQ(*s.truth[0], cv::Rect2d(10, 20, 30, 40));  // 0-based: unchanged
  EXPECT_EQ(*s.truth[1], cv::Rect2d(10, 10, 20, 20));
  EXPECT_FALSE(s.truth[2]);
  EXPECT_FALSE(s.truth[3]);
  EXPECT_EQ(s.notes.size(), 2u);  // the short file, the NaN box
}

TEST_F(BenchmarkSequenceTest, ImagesBesideTheGroundTruthAndALongerFile) {
  const fs::path seq = dir_ / "flat";
  image(seq / "a1.png");
  image(seq / "a2.png");
  text(seq / "groundtruth.txt", "1,2,3,4\n1,2,3,4\n1,2,3,4\n1,2,0,4\n");
  const ap::io::BenchmarkSequence s = ap::io::readBenchmarkSequence(seq.string());
  ASSERT_EQ(s.frames.size(), 2u);
  ASSERT_EQ(s.truth.size(), 2u);
  ASSERT_EQ(s.notes.size(), 2u);
  EXPECT_NE(s.notes[0].find("the last 2 are ignored"), std::string::npos) << s.notes[0];
}

TEST_F(BenchmarkSequenceTest, ErrorsNameTheFolderFileAndLine) {
  auto message = [](const std::string& dir) {
    try {
      ap::io::readBenchmarkSequence(dir);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message((dir_ / "missing").string()).find("no such sequence folder"),
            std::string::npos);
  fs::create_directories(dir_ / "empty");
  EXPECT_NE(message((dir_ / "empty").string()).find("no ground truth"), std::string::npos);
  const fs::path seq = dir_ / "bad";
  image(seq / "img" / "0001.jpg");
  image(seq / "img" / "0002.jpg");
  text(seq / "groundtruth_rect.txt", "1,2,3,4\n1,2,three,4\n");
  const std::string m = message(seq.string());
  EXPECT_NE(m.find("groundtruth_rect.txt:2"), std::string::npos) << m;
  text(seq / "groundtruth_rect.txt", "1,2,3\n");
  EXPECT_NE(message(seq.string()).find("groundtruth_rect.txt:1: 3 values"), std::string::npos);
  text(seq / "groundtruth_rect.txt", "nan,nan,nan,nan\n1,2,3,4\n");
  EXPECT_NE(message(seq.string()).find("first frame has no box"), std::string::npos);
  const fs::path noimg = dir_ / "noimg";
  fs::create_directories(noimg / "img");
  text(noimg / "groundtruth_rect.txt", "1,2,3,4\n");
  EXPECT_NE(message(noimg.string()).find("no image"), std::string::npos);
}

}  // namespace
