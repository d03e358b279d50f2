// io::readLabelMask and io::pairImagesWithMasks on masks written here the ways benchmarks ship
// them: grey class ids, palette colours (as OpenCV expands a VOC palette PNG), another resolution.
#include "adaptive_perception/io/label_mask.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>

#include "../refusal.h"
#include "../scratch_dir.h"

namespace ap = adaptive_perception;
namespace fs = std::filesystem;
using ap::test_support::refusal;

namespace {

class LabelMaskTest : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const cv::Mat& m) const {
    const std::string p = (dir_ / name).string();
    fs::create_directories(fs::path(p).parent_path());
    EXPECT_TRUE(cv::imwrite(p, m));
    return p;
  }
  ap::test_support::ScratchDir scratch_{"label_mask"};
  const fs::path& dir_ = scratch_.path();
};

TEST(VocPalette, FirstEntriesAreThePublishedColours) {
  // RGB (128, 0, 0), (0, 128, 0), (128, 128, 0), (0, 0, 128), (64, 0, 0) for indices 1, 2, 3, 4, 8.
  EXPECT_EQ(ap::io::vocPaletteBgr(0), cv::Vec3b(0, 0, 0));
  EXPECT_EQ(ap::io::vocPaletteBgr(1), cv::Vec3b(0, 0, 128));
  EXPECT_EQ(ap::io::vocPaletteBgr(2), cv::Vec3b(0, 128, 0));
  EXPECT_EQ(ap::io::vocPaletteBgr(3), cv::Vec3b(0, 128, 128));
  EXPECT_EQ(ap::io::vocPaletteBgr(4), cv::Vec3b(128, 0, 0));
  EXPECT_EQ(ap::io::vocPaletteBgr(8), cv::Vec3b(0, 0, 64));
}

TEST_F(LabelMaskTest, GreyAndPaletteMasksGiveTheSameClasses) {
  cv::Mat ids(6, 8, CV_8UC1, cv::Scalar(0));
  ids(cv::Rect(0, 3, 8, 3)).setTo(3);
  ids(cv::Rect(2, 0, 1, 6)).setTo(2);
  cv::Mat colour(ids.size(), CV_8UC3);
  for (int r = 0; r < ids.rows; ++r)
    for (int c = 0; c < ids.cols; ++c)
      colour.at<cv::Vec3b>(r, c) = ap::io::vocPaletteBgr(ids.at<std::uint8_t>(r, c));
  const cv::Mat grey = ap::io::readLabelMask(write("grey.png", ids), ids.size());
  bool scaled = true;
  const cv::Mat pal = ap::io::readLabelMask(write("palette.png", colour), ids.size(), &scaled);
  EXPECT_FALSE(scaled);
  EXPECT_EQ(cv::countNonZero(grey != ids), 0);
  EXPECT_EQ(cv::countNonZero(pal != ids), 0);
}

TEST_F(LabelMaskTest, AColourOutsideThePaletteIsNamed) {
  cv::Mat colour(4, 4, CV_8UC3, cv::Scalar(0, 0, 0));
  colour.at<cv::Vec3b>(1, 2) = cv::Vec3b(10, 200, 30);
  const std::string p = write("odd.png", colour);
  const std::string msg =
      refusal<std::runtime_error>([&] { ap::io::readLabelMask(p, colour.size()); });
  EXPECT_NE(msg.find(p), std::string::npos) << msg;
  EXPECT_NE(msg.find("(2, 1)"), std::string::npos) << msg;
}

TEST_F(LabelMaskTest, AnotherResolutionIsScaledByNearestNeighbour) {
  // 8 x 6 (4:3) drawn for a 5 x 4 image (5:4, 6.7% apart): scaled, class ids kept (no blending).
  cv::Mat ids(6, 8, CV_8UC1, cv::Scalar(0));
  ids(cv::Rect(0, 3, 8, 3)).setTo(3);
  bool scaled = false;
  const cv::Mat m = ap::io::readLabelMask(write("big.png", ids), {5, 4}, &scaled);
  EXPECT_TRUE(scaled);
  ASSERT_EQ(m.size(), cv::Size(5, 4));
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 5; ++c) {
      const int v = m.at<std::uint8_t>(r, c);
      EXPECT_TRUE(v == 0 || v == 3) << v;
    }
  EXPECT_EQ(m.at<std::uint8_t>(0, 0), 0);
  EXPECT_EQ(m.at<std::uint8_t>(3, 4), 3);
}

TEST_F(LabelMaskTest, AMaskOfAnotherShapeIsRefusedNamingTheFile) {
  const cv::Mat ids(6, 8, CV_8UC1, cv::Scalar(0));
  const std::string p = write("wide.png", ids);
  const std::string msg = refusal<std::runtime_error>([&] { ap::io::readLabelMask(p, {6, 8}); });
  EXPECT_NE(msg.find(p), std::string::npos) << msg;
  EXPECT_NE(msg.find("aspect"), std::string::npos) << msg;
  EXPECT_NE(refusal<std::runtime_error>([&] {
              ap::io::readLabelMask((dir_ / "missing.png").string(), {8, 6});
            }).find("missing.png"),
            std::string::npos);
}

TEST_F(LabelMaskTest, ImagesArePairedWithMasksByName) {
  const cv::Mat img(4, 4, CV_8UC3, cv::Scalar(0, 100, 0)), mask(4, 4, CV_8UC1, cv::Scalar(3));
  write("images/b.jpg", img);
  write("images/a.jpg", img);
  write("masks/a.png", mask);
  write("masks/b.png", mask);
  const auto pairs =
      ap::io::pairImagesWithMasks((dir_ / "images").string(), (dir_ / "masks").string());
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(fs::path(pairs[0].mask_path).filename(), "a.png");
  EXPECT_EQ(fs::path(pairs[1].mask_path).filename(), "b.png");
  write("images/c.jpg", img);  // no mask
  const std::string msg = refusal<std::runtime_error>(
      [&] { ap::io::pairImagesWithMasks((dir_ / "images").string(), (dir_ / "masks").string()); });
  EXPECT_NE(msg.find("c.jpg"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no mask"), std::string::npos) << msg;
}

}  // namespace
