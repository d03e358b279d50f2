// The list of images with head angles (evaluate_field_localization's --list): both headers, empty
// truth, relative paths, and errors with the file, line and column.
#include "adaptive_perception/io/head_image_list.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../scratch_dir.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;

namespace {
std::string errorOf(const std::string& csv, const std::string& text) {
  std::ofstream(csv) << text;
  try {
    io::readHeadImageList(csv);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(HeadImageList, ReadsBothHeadersTruthAndPaths) {
  const test_support::ScratchDir scratch("ap_head_list");
  const fs::path& dir = scratch.path();
  const std::string csv = (dir / "list.csv").string();
  std::ofstream(csv) << "image,head_pitch_rad,head_yaw_rad,x_m,y_m\n# comment\n"
                        "p1/top.jpg,0.078,0.014,1.626,1.004\n/abs/b.jpg, -0.13 ,0.5,,\r\n";
  const auto list = io::readHeadImageList(csv);
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list[0].path, (dir / "p1/top.jpg").string());
  EXPECT_DOUBLE_EQ(list[0].head_pitch_rad, 0.078);
  EXPECT_DOUBLE_EQ(list[0].head_yaw_rad, 0.014);
  ASSERT_TRUE(list[0].truth_xy_m.has_value());
  EXPECT_DOUBLE_EQ(list[0].truth_xy_m->x(), 1.626);
  EXPECT_DOUBLE_EQ(list[0].truth_xy_m->y(), 1.004);
  EXPECT_EQ(list[0].line, 3);
  EXPECT_EQ(list[1].path, "/abs/b.jpg");
  EXPECT_DOUBLE_EQ(list[1].head_pitch_rad, -0.13);
  EXPECT_FALSE(list[1].truth_xy_m.has_value());

  EXPECT_FALSE(list[0].torso_pitch_rad.has_value());

  std::ofstream(csv) << "image,head_pitch_rad,head_yaw_rad\na.jpg,0,0\n";
  const auto short_list = io::readHeadImageList(csv);
  ASSERT_EQ(short_list.size(), 1u);
  EXPECT_FALSE(short_list[0].truth_xy_m.has_value());

  std::ofstream(csv) << "image,head_pitch_rad,head_yaw_rad,x_m,y_m,torso_pitch_rad\n"
                        "a.jpg,0,0,1,2,-0.142\nb.jpg,0,0,,,\nc.jpg,0,0,,,0.008\n";
  const auto torso = io::readHeadImageList(csv);
  ASSERT_EQ(torso.size(), 3u);
  ASSERT_TRUE(torso[0].torso_pitch_rad.has_value());
  EXPECT_DOUBLE_EQ(*torso[0].torso_pitch_rad, -0.142);
  EXPECT_DOUBLE_EQ(torso[0].truth_xy_m->y(), 2.0);
  EXPECT_FALSE(torso[1].torso_pitch_rad.has_value());
  EXPECT_FALSE(torso[2].truth_xy_m.has_value());
  EXPECT_DOUBLE_EQ(*torso[2].torso_pitch_rad, 0.008);
}

TEST(HeadImageList, ErrorsNameTheFileLineAndColumn) {
  const test_support::ScratchDir scratch("ap_head_list_errors");
  const std::string csv = (scratch.path() / "list.csv").string();
  const auto has = [](const std::string& what, const std::string& part) {
    return what.find(part) != std::string::npos;
  };
  EXPECT_TRUE(has(errorOf(csv, "image,pitch,yaw\n"), "list.csv:1: expected the header"));
  EXPECT_TRUE(has(errorOf(csv, "image,head_pitch_rad,head_yaw_rad,x_m,y_m\na.jpg,0,0,1\n"),
                  "list.csv:2: expected 5 columns"));
  EXPECT_TRUE(has(errorOf(csv, "image,head_pitch_rad,head_yaw_rad\na.jpg,0\n"),
                  "list.csv:2: expected 3 columns"));
  EXPECT_TRUE(has(errorOf(csv, "image,head_pitch_rad,head_yaw_rad\na.jpg,0.1x,0\n"),
                  "list.csv:2: head_pitch_rad '0.1x' is not a finite number"));
  EXPECT_TRUE(has(errorOf(csv, "image,head_pitch_rad,head_yaw_rad\na.jpg,0,nan\n"),
                  "head_yaw_rad 'nan' is not a finite number"));
  EXPECT_TRUE(has(errorOf(csv, "image,head_pitch_rad,head_yaw_rad,x_m,y_m\na.jpg,0,0,1,\n"),
                  "list.csv:2: x_m and y_m are given together"));
  EXPECT_TRUE(has(errorOf(csv, "image,head_pitch_rad,head_yaw_rad\n,0,0\n"),
                  "list.csv:2: the image column is empty"));
  EXPECT_TRUE(has(errorOf(csv, "image,head_pitch_rad,head_yaw_rad,x_m\na.jpg,0,0,1\n"),
                  "list.csv:1: expected the header"));
  EXPECT_TRUE(has(errorOf(csv, "image,head_pitch_rad,head_yaw_rad,x_m,y_m,torso_pitch_rad\n"
                               "a.jpg,0,0,1,2,up\n"),
                  "list.csv:2: torso_pitch_rad 'up' is not a finite number"));
  EXPECT_TRUE(has(errorOf(csv, "# nothing\n"), "list.csv: empty (no header)"));
  EXPECT_TRUE(has(errorOf((scratch.path() / "none" / "x.csv").string(), ""), "cannot open"));
}
