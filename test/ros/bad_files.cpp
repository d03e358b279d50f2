// rostest: every node given an empty, corrupt or foreign file (field map, colour priors, place
// database, tracking dynamics, line map) must stop at start-up with an error naming the file, and leave the
// file byte for byte as it was.
#include <gtest/gtest.h>
#include <ros/package.h>
#include <ros/ros.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "rostest_support.h"

namespace fs = std::filesystem;

namespace {

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeAll(const fs::path& p, const std::string& s) {
  std::ofstream out(p, std::ios::binary);
  out << s;
}

using NodeRun = adaptive_perception::rostest_support::CommandRun;

/// Runs `rosrun adaptive_perception NODE ARGS` (stdout and stderr together) for at most 30 s, as
/// the node PREFIX + NODE (private parameters set on the command line stay on the parameter
/// server: each group of tests names its nodes apart).
NodeRun runNode(const std::string& node, const std::string& args,
                const std::string& prefix = "bad_files_") {
  return adaptive_perception::rostest_support::runCommand(
      "rosrun adaptive_perception " + node + " __name:=" + prefix + node + " " + args, 30);
}

struct Case {
  std::string node, name;
  std::string param;     // the node's parameter naming the file (or directory)
  std::string file;      // the file written, relative to the case's directory
  std::string contents;  // what it holds
  bool pass_dir = false; // the parameter names the directory (priors_dir), not the file
};

class BadFiles : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ap_bad_files_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    pkg_ = ros::package::getPath("adaptive_perception");
    ASSERT_FALSE(pkg_.empty());
  }
  void TearDown() override { fs::remove_all(dir_); }

  void check(const Case& c, const std::string& extra_args = "") {
    SCOPED_TRACE(c.node + ": " + c.name);
    const fs::path case_dir = dir_ / (c.node + "_" + std::to_string(counter_++));
    fs::create_directories(case_dir);
    const fs::path file = case_dir / c.file;
    writeAll(file, c.contents);
    const auto before = fs::last_write_time(file);
    const std::string target = c.pass_dir ? case_dir.string() : file.string();
    const NodeRun r = runNode(c.node, "_" + c.param + ":=" + target + " " + extra_args);
    std::printf("bad_files: %s, %s: exit %d: %s", c.node.c_str(), c.name.c_str(), r.status,
                r.output.substr(r.output.rfind('\n', r.output.size() - 2) + 1).c_str());
    EXPECT_EQ(r.status, 1) << "the node did not stop with an error; output:\n" << r.output;
    EXPECT_NE(r.output.find(file.filename().string()), std::string::npos)
        << "the error does not name the file; output:\n"
        << r.output;
    EXPECT_EQ(readAll(file), c.contents) << "the file was changed";
    EXPECT_EQ(fs::last_write_time(file), before) << "the file was rewritten";
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(case_dir)) ++entries;
    EXPECT_EQ(entries, 1u) << "the node left other files beside it";
  }

  fs::path dir_;
  std::string pkg_;
  int counter_ = 0;
};

const char kGarbage[] = "\x89PNG\r\n\x1a\n this is not what the node expects \x01\x02\x03\xff";

TEST_F(BadFiles, FieldMaps) {
  const std::string real = readAll(pkg_ + "/config/field_4legged.yaml");
  ASSERT_GT(real.size(), 100u);
  for (const std::string node : {"field_map_publisher", "color_estimator", "rbpf_localizer"}) {
    check({node, "empty field map", "field_file", "field.yaml", ""});
    check({node, "binary field map", "field_file", "field.yaml", std::string(kGarbage, sizeof kGarbage - 1)});
    // The first half of the real file: only its comments survive.
    check({node, "truncated field map", "field_file", "field.yaml", real.substr(0, real.size() / 2)});
    check({node, "YAML syntax error", "field_file", "field.yaml", "field_length_m: [5.4\n"});
  }
}

TEST_F(BadFiles, ColorPriors) {
  const std::string real = readAll(pkg_ + "/config/color_priors/dark.yaml");
  ASSERT_GT(real.size(), 100u);
  for (const std::string node : {"color_estimator", "rbpf_localizer"}) {
    // priors_dir names the directory; the node wants dark.yaml and bright.yaml in it.
    check({node, "empty prior", "priors_dir", "dark.yaml", "", true},
          "_filter:=single _single_prior:=dark");
    check({node, "truncated prior", "priors_dir", "dark.yaml", real.substr(0, real.size() / 3), true},
          "_filter:=single _single_prior:=dark");
    check({node, "prior of another type", "priors_dir", "dark.yaml", "[1, 2, 3]\n", true},
          "_filter:=single _single_prior:=dark");
  }
}

TEST_F(BadFiles, PlaceDatabases) {
  for (const std::string node : {"histogram_place_recognizer", "appearance_localizer"}) {
    check({node, "corrupt database", "database", "places.sqlite",
           std::string(kGarbage, sizeof kGarbage - 1) + std::string(4096, 'x')});
    // An SQLite header over nonsense pages.
    check({node, "truncated database", "database", "places.sqlite",
           std::string("SQLite format 3\0", 16) + std::string(100, '\x07')});
  }
}

TEST_F(BadFiles, TrackingDynamics) {
  check({"condensation_tracker", "empty dynamics", "dynamics", "dynamics.yaml", ""});
  check({"condensation_tracker", "dynamics of the wrong size", "dynamics", "dynamics.yaml",
         "A1: [1, 2, 3]\nA0: [0]\nd: [0]\nB: [1]\n"});
}

TEST_F(BadFiles, LineMaps) {
  check({"ekf_slam_mapper", "empty line map", "initial_map", "map.yaml", ""});
  check({"ekf_slam_mapper", "binary line map", "initial_map", "map.yaml",
         std::string(kGarbage, sizeof kGarbage - 1)});
  check({"ekf_slam_mapper", "line map without rho", "initial_map", "map.yaml",
         "landmarks:\n  - {id: 1, alpha_rad: 0.1}\nstate_covariance: {dim: 5, data: "
         "[1,0,0,0,0, 0,1,0,0,0, 0,0,1,0,0, 0,0,0,1,0, 0,0,0,0,1]}\n"});
  check({"ekf_slam_mapper", "line map with a covariance of the wrong size", "initial_map",
         "map.yaml", "landmarks: []\nstate_covariance: {dim: 3, data: [1, 0, 0, 1]}\n"});
}

// Settings that used to be taken at start-up and fail later (issue 27): each must stop the node
// at once with a message naming the parameter.
TEST(BadSettings, FrameIdsThatTf2WouldRefuseStopTheNodeAtStartUp) {
  struct Setting {
    std::string node, args, param;
  };
  for (const Setting& s : std::vector<Setting>{
           {"rbpf_localizer", "_map_frame:=/map", "map_frame"},
           {"ekf_slam_mapper", "\"_odom_frame:=my odom\"", "odom_frame"},
           {"color_estimator", "_map_frame:=map//x", "map_frame"}}) {
    SCOPED_TRACE(s.node + " " + s.args);
    const NodeRun r = runNode(s.node, s.args, "bad_settings_");
    EXPECT_EQ(r.status, 1) << "the node did not stop; output:\n" << r.output;
    EXPECT_NE(r.output.find(s.param), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("not a tf frame id"), std::string::npos) << r.output;
  }
}

TEST(BadSettings, AParticleCountThatWouldNotFitInMemoryStopsTheNodeWithTheEstimate) {
  const NodeRun r = runNode("rbpf_localizer", "_particles:=1000000", "bad_particles_");
  EXPECT_EQ(r.status, 1) << "the node did not stop; output:\n" << r.output;
  EXPECT_NE(r.output.find("particles = 1000000 would take about"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("at most"), std::string::npos) << r.output;
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "bad_files");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
