// evaluate_places' traversal protocol as a user runs it: two drives of the indoor simulator's
// route under other light (cloudy reference, night query) written as image folders, matched with
// the default configuration; then bad input (an image that cannot be read, a list naming a
// missing file, a malformed ground-truth line), each refused with an error naming it, the user's
// folders left as they were.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "rostest_support.h"

namespace fs = std::filesystem;
using adaptive_perception::rostest_support::CommandRun;
using adaptive_perception::rostest_support::runCommand;

namespace {

std::string summaryValue(const std::string& output, const std::string& key) {
  const auto line = output.rfind("evaluate_places: mode=traversal");
  if (line == std::string::npos) return "";
  const auto k = output.find(" " + key + "=", line);
  if (k == std::string::npos) return "";
  const auto a = k + key.size() + 2;
  return output.substr(a, output.find_first_of(" \n", a) - a);
}

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> s;
  for (const auto& e : fs::directory_iterator(dir))
    s.insert(e.path().filename().string() + ":" + std::to_string(fs::file_size(e.path())));
  return s;
}

class PlaceTraversalTool : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("ap_place_traversal_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    for (const char* light : {"cloudy", "night"}) {
      const CommandRun r = runCommand(
          "rosrun adaptive_perception simulate_indoor --lighting " + std::string(light) +
              " --seed 3 --camera perspective --width_px 160 --height_px 120 --camera_rate_hz 1" +
              " --output " + (dir_ / (std::string(light) + ".bag")).string() + " --images_out " +
              (dir_ / light).string(),
          240);
      ASSERT_EQ(r.status, 0) << r.output;
    }
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }

  static CommandRun evaluate(const std::string& args) {
    return runCommand("rosrun adaptive_perception evaluate_places " + args + " --output " +
                          (dir_ / "out").string(),
                      240);
  }
  static fs::path dir_;
};
fs::path PlaceTraversalTool::dir_;

TEST_F(PlaceTraversalTool, RecognisesTheRouteAtNightFromACloudyDrive) {
  const auto before = listing(dir_ / "cloudy");
  const CommandRun r = evaluate("--reference " + (dir_ / "cloudy").string() + " --query " +
                                (dir_ / "night").string() + " --tolerance_frames 2");
  std::printf("%s", r.output.substr(r.output.rfind("  method")).c_str());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(summaryValue(r.output, "method"), "route");
  // Measured 1.000 with the sequence search (the thumbnail alone 0.919, the gradients alone 0.977).
  EXPECT_GE(std::stod(summaryValue(r.output, "recall_at_1")), 0.9);
  EXPECT_GE(std::stod(summaryValue(r.output, "pr_auc")), 0.9);
  EXPECT_GT(std::stoi(summaryValue(r.output, "queries")), 400);
  for (const char* f : {"results.yaml", "queries.csv", "pr_curves.csv"})
    EXPECT_TRUE(fs::exists(dir_ / "out" / f)) << f;
  EXPECT_EQ(listing(dir_ / "cloudy"), before) << "the reference folder was changed";
}

TEST_F(PlaceTraversalTool, AStoredReferenceTraversalGivesTheSameAnswers) {
  const fs::path db = dir_ / "cloudy.db";
  const std::string query = " --query " + (dir_ / "night").string() + " --tolerance_frames 2";
  const CommandRun built =
      evaluate("--reference " + (dir_ / "cloudy").string() + " --database " + db.string() + query);
  ASSERT_EQ(built.status, 0) << built.output;
  ASSERT_TRUE(fs::exists(db));
  const auto stored = fs::file_size(db);
  const auto mtime = fs::last_write_time(db);
  // From the database alone, and with the same reference folder: the same figures.
  for (const std::string& ref : {std::string(), " --reference " + (dir_ / "cloudy").string()}) {
    const CommandRun again = evaluate("--database " + db.string() + ref + query);
    ASSERT_EQ(again.status, 0) << again.output;
    for (const char* key : {"recall_at_1", "recall_at_5", "pr_auc", "references"})
      EXPECT_EQ(summaryValue(again.output, key), summaryValue(built.output, key)) << key;
  }
  // Another reference folder than the stored one is refused, and the database left as it was.
  const CommandRun other =
      evaluate("--reference " + (dir_ / "night").string() + " --database " + db.string() + query);
  EXPECT_EQ(other.status, 1) << other.output;
  EXPECT_NE(other.output.find("reference 1 is '"), std::string::npos) << other.output;
  EXPECT_EQ(fs::file_size(db), stored);
  EXPECT_EQ(fs::last_write_time(db), mtime);
}

TEST_F(PlaceTraversalTool, AFailedBuildLeavesNoDatabase) {
  const fs::path ref = dir_ / "bad_ref_db";
  fs::create_directories(ref);
  fs::copy_file(dir_ / "cloudy" / "00000.png", ref / "00000.png");
  std::ofstream(ref / "00001.png") << "not an image";
  const fs::path db = dir_ / "bad.db";
  const CommandRun r = evaluate("--reference " + ref.string() + " --database " + db.string() +
                                " --query " + (dir_ / "night").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("00001.png' cannot be read"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(db));
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find("bad.db"), std::string::npos) << e.path();
}

TEST_F(PlaceTraversalTool, AnImageThatCannotBeReadIsNamed) {
  const fs::path ref = dir_ / "bad_ref";
  fs::create_directories(ref);
  fs::copy_file(dir_ / "cloudy" / "00000.png", ref / "00000.png");
  std::ofstream(ref / "00001.png") << "not an image";
  const auto before = listing(ref);
  const CommandRun r =
      evaluate("--reference " + ref.string() + " --query " + (dir_ / "night").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("00001.png' cannot be read"), std::string::npos) << r.output;
  EXPECT_EQ(listing(ref), before);
}

TEST_F(PlaceTraversalTool, AListNamingAMissingFileIsNamed) {
  const fs::path list = dir_ / "query.csv";
  std::ofstream(list) << "image_path\n"
                      << (dir_ / "night" / "00000.png").string() << "\nmissing.png\n";
  const CommandRun r =
      evaluate("--reference " + (dir_ / "cloudy").string() + " --query " + list.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("missing.png' cannot be read"), std::string::npos) << r.output;
}

TEST_F(PlaceTraversalTool, AMalformedGroundTruthLineIsNamed) {
  const fs::path gt = dir_ / "gt.csv";
  std::ofstream(gt) << "query_idx,ref_idx,tolerance\n1,1,2\n2;2;2\n";
  const CommandRun r = evaluate("--reference " + (dir_ / "cloudy").string() + " --query " +
                                (dir_ / "night").string() + " --ground_truth " + gt.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("gt.csv:3:"), std::string::npos) << r.output;
  std::ofstream(gt) << "1,99999,2\n";
  const CommandRun beyond = evaluate("--reference " + (dir_ / "cloudy").string() + " --query " +
                                     (dir_ / "night").string() + " --ground_truth " + gt.string());
  EXPECT_EQ(beyond.status, 1) << beyond.output;
  EXPECT_NE(beyond.output.find("beyond the traversals"), std::string::npos) << beyond.output;
}

TEST_F(PlaceTraversalTool, BadOptionsGetTheUsage) {
  const CommandRun r = evaluate("--reference " + (dir_ / "cloudy").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("needs --query B and --reference A"), std::string::npos) << r.output;
  const CommandRun m = evaluate("--reference " + (dir_ / "cloudy").string() + " --query " +
                                (dir_ / "night").string() + " --method nearest");
  EXPECT_EQ(m.status, 1) << m.output;
  EXPECT_NE(m.output.find("method 'nearest'"), std::string::npos) << m.output;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "place_traversal_tool");
  return RUN_ALL_TESTS();
}
