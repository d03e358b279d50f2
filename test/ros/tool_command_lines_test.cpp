// The tools' command lines (src/tools/command_line.h): what CommandLine accepts and refuses, and
// every built tool answering --help and refusing an unknown option.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <utility>
#include <vector>

#include "../../src/tools/command_line.h"
#include "../core/scratch_dir.h"
#include "adaptive_perception/config/enum_names.h"

namespace {

using adaptive_perception::test_support::ScratchDir;
using adaptive_perception::tools::CommandLine;
namespace config = adaptive_perception::config;
namespace fs = std::filesystem;

struct Settings {
  int count = 3;
  double gain = 0.5;
  bool enabled = false;
  static const config::Fields<Settings>& fields() {
    static const config::Fields<Settings> f =
        config::Fields<Settings>()
            .add("count", &Settings::count, config::closed(1, 10), "how many")
            .add("gain", &Settings::gain, config::belowOne(), "a fraction")
            .add("enabled", &Settings::enabled, "on or off");
    return f;
  }
};
struct Other {  // shares "gain" with Settings
  double gain = 0.25;
  static const config::Fields<Other>& fields() {
    static const config::Fields<Other> f =
        config::Fields<Other>().add("gain", &Other::gain, config::belowOne(), "a fraction");
    return f;
  }
};

// Parses `words` (after the program name) with `cli`.
void parseWords(CommandLine& cli, const std::vector<std::string>& words) {
  std::vector<std::string> all = {cli.name()};
  all.insert(all.end(), words.begin(), words.end());
  std::vector<char*> argv;
  for (std::string& w : all) argv.push_back(w.data());
  cli.parse(static_cast<int>(argv.size()), argv.data());
}

// Parses `words` (after the program name) with a command line of one string option, one real
// option in (0, 10], one flag and Settings' and Other's tables.
struct Parsed {
  std::string name = "default";
  double length_m = 1.0;
  bool force = false;
  Settings settings;
  Other other;
};
void parse(const std::vector<std::string>& words, Parsed* p) {
  CommandLine cli("demo", "A test of the command line.");
  cli.option("name", &p->name, "a name");
  cli.option("length_m", &p->length_m, config::aboveZero(10), "a length, m");
  cli.flag("force", &p->force, "a flag");
  cli.fields(Settings::fields(), &p->settings);
  cli.fields(Other::fields(), &p->other);
  parseWords(cli, words);
}

TEST(CommandLine, KeepsDefaultsAndSetsWhatIsGiven) {
  Parsed d;
  parse({}, &d);
  EXPECT_EQ(d.name, "default");
  EXPECT_EQ(d.length_m, 1.0);
  EXPECT_FALSE(d.force);
  EXPECT_EQ(d.settings.count, 3);

  Parsed p;
  parse({"--name", "x", "--length_m=2.5", "--force", "--count", "7", "--enabled", "true"}, &p);
  EXPECT_EQ(p.name, "x");
  EXPECT_EQ(p.length_m, 2.5);
  EXPECT_TRUE(p.force);
  EXPECT_EQ(p.settings.count, 7);
  EXPECT_TRUE(p.settings.enabled);
}

TEST(CommandLine, AFieldNameSharedByTwoTablesSetsBoth) {
  Parsed p;
  parse({"--gain", "0.75"}, &p);
  EXPECT_EQ(p.settings.gain, 0.75);
  EXPECT_EQ(p.other.gain, 0.75);
}

TEST(CommandLine, RefusesWhatItCannotTakeNamingIt) {
  testing::FLAGS_gtest_death_test_style = "threadsafe";
  // The words given, and what the message must name.
  const std::vector<std::pair<std::vector<std::string>, std::string>> refused = {
      {{"--no_such_option", "1"}, "no_such_option"},
      {{"--length_m", "0"}, "length_m.*0 is out of range \\(0, 10\\]"},
      {{"--length_m", "abc"}, "length_m.*expects a number, got 'abc'"},
      {{"--count", "2.5"}, "count.*expects an integer, got '2.5'"},
      {{"--count", "11"}, "count.*11 is out of range \\[1, 10\\]"},
      {{"--gain", "1"}, "gain.*1 is out of range \\[0, 1\\)"},
      {{"--enabled", "yes please"}, "enabled.*expects 0, 1, true or false"},
      // A flag takes no value: the word after it is refused, not swallowed.
      {{"--force", "file.bag"}, "file.bag"},
  };
  Parsed p;
  for (const auto& [words, message] : refused)
    EXPECT_EXIT(parse(words, &p), testing::ExitedWithCode(2), message) << words[0];
}

TEST(CommandLine, HelpListsEveryOptionWithItsDefaultAndRange) {
  Parsed p;
  EXPECT_EXIT(parse({"--help"}, &p), testing::ExitedWithCode(0), "");
  CommandLine cli("demo", "A test of the command line.");
  cli.option("length_m", &p.length_m, config::aboveZero(10), "a length, m");
  cli.fields(Settings::fields(), &p.settings);
  const std::string help = cli.help();
  EXPECT_NE(help.find("A test of the command line."), std::string::npos) << help;
  EXPECT_NE(help.find("--length_m FLOAT:in (0, 10]"), std::string::npos) << help;
  EXPECT_NE(help.find("a length, m (default: 1)"), std::string::npos) << help;
  EXPECT_NE(help.find("--count INT:in [1, 10]"), std::string::npos) << help;
  EXPECT_NE(help.find("how many (default: 3)"), std::string::npos) << help;
  EXPECT_NE(help.find("--gain FLOAT:in [0, 1)"), std::string::npos) << help;
  EXPECT_NE(help.find("a fraction (default: 0.5)"), std::string::npos) << help;
  EXPECT_NE(help.find("--enabled BOOL"), std::string::npos) << help;
  EXPECT_NE(help.find("on or off (default: false)"), std::string::npos) << help;
}

// A tool with --seed and --overwrite, as the writing tools declare them; parses `words` and then
// refuses `path` if it exists without --overwrite. Returns the parsed seed.
std::uint64_t parseWriter(const std::vector<std::string>& words, const std::string& path) {
  CommandLine cli("writer", "A test of --seed and --overwrite.");
  const std::uint64_t& seed = cli.seed();
  const bool& overwrite = cli.overwrite("the file");
  parseWords(cli, words);
  cli.refuseExisting(path);
  EXPECT_EQ(overwrite, std::find(words.begin(), words.end(), "--overwrite") != words.end());
  return seed;
}

TEST(CommandLine, SeedDefaultsToOneAndAnExistingFileIsReplacedOnlyWithOverwrite) {
  testing::FLAGS_gtest_death_test_style = "threadsafe";
  const fs::path dir =
      fs::temp_directory_path() / ("tool_command_lines_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string absent = (dir / "absent.bag").string(),
                    present = (dir / "present.bag").string();
  std::FILE* f = std::fopen(present.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fclose(f);

  EXPECT_EQ(parseWriter({}, absent), 1u);
  EXPECT_EQ(parseWriter({"--seed", "42"}, absent), 42u);
  EXPECT_EXIT(parseWriter({}, present), testing::ExitedWithCode(2),
              "present.bag' exists; pass --overwrite to replace it");
  EXPECT_EQ(parseWriter({"--overwrite"}, present), 1u);
  EXPECT_TRUE(fs::exists(present)) << "refuseExisting only checks; it never removes a file";

  CommandLine cli("writer", "A test of --seed and --overwrite.");
  cli.seed();
  cli.overwrite("the file");
  const std::string help = cli.help();
  EXPECT_NE(help.find("random seed: the same seed repeats a run exactly (default: 1)"),
            std::string::npos)
      << help;
  EXPECT_NE(help.find("replace the file if it exists"), std::string::npos) << help;
  fs::remove_all(dir);
}

// An option that takes one of a few words (CommandLine::word): the word parsed into the enum, the
// default shown by --help with the allowed words, any other word refused naming them.
enum class Shape { kCircle, kSquare };
const config::EnumNames<Shape>& shapes() {
  static const config::EnumNames<Shape> names(
      "shape", {{Shape::kCircle, "circle"}, {Shape::kSquare, "square"}}, {{Shape::kSquare, "box"}});
  return names;
}
Shape parseShape(const std::vector<std::string>& words) {
  CommandLine cli("demo", "A test of word options.");
  Shape shape = Shape::kCircle;
  cli.word("shape", &shape, shapes(), "the shape drawn");
  parseWords(cli, words);
  return shape;
}

TEST(CommandLine, AWordOptionTakesOneOfItsWords) {
  testing::FLAGS_gtest_death_test_style = "threadsafe";
  EXPECT_EQ(parseShape({}), Shape::kCircle);
  EXPECT_EQ(parseShape({"--shape", "square"}), Shape::kSquare);
  EXPECT_EQ(parseShape({"--shape=box"}), Shape::kSquare);  // an alias
  EXPECT_EXIT(parseShape({"--shape", "cube"}), testing::ExitedWithCode(2),
              "shape = 'cube' \\(allowed: circle, square\\)");
  CommandLine cli("demo", "A test of word options.");
  Shape shape = Shape::kSquare;
  cli.word("shape", &shape, shapes(), "the shape drawn");
  const std::string help = cli.help();
  EXPECT_NE(help.find("one of circle, square"), std::string::npos) << help;
  EXPECT_NE(help.find("the shape drawn (default: square)"), std::string::npos) << help;
}

// The tools' standard files: --bag (inputBag) must name a file that exists; --output as a
// results folder defaults to results/<tool name>; --output as the one file written (outputFile)
// is refused at parse() where it exists, unless --overwrite is given.
TEST(CommandLine, TheStandardInputAndOutputOptions) {
  testing::FLAGS_gtest_death_test_style = "threadsafe";
  const ScratchDir dir("tool_command_lines");
  const std::string present = dir.file("present.bag"), absent = dir.file("absent.bag");
  std::FILE* f = std::fopen(present.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fclose(f);

  auto reader = [](const std::vector<std::string>& words) {
    CommandLine cli("evaluate_demo", "A test of --bag and --output.");
    const std::string& bag = cli.inputBag("the bag read");
    const std::string& output = cli.resultsFolder("the results");
    parseWords(cli, words);
    return std::make_pair(bag, output);
  };
  EXPECT_EQ(reader({"--bag", present}),
            std::make_pair(present, std::string("results/evaluate_demo")));
  EXPECT_EQ(reader({"--bag", present, "--output", "elsewhere"}).second, "elsewhere");
  EXPECT_EXIT(reader({"--bag", absent}), testing::ExitedWithCode(2), "absent.bag");
  EXPECT_EXIT(reader({}), testing::ExitedWithCode(2), "--bag is required");

  auto writer = [](const std::vector<std::string>& words) {
    CommandLine cli("simulate_demo", "A test of --output as a file.");
    const std::string& output = cli.outputFile("the bag to write", "the bag");
    parseWords(cli, words);
    return std::make_pair(output, cli.overwriteGiven());
  };
  EXPECT_EQ(writer({"--output", absent}), std::make_pair(absent, false));
  EXPECT_EXIT(writer({"--output", present}), testing::ExitedWithCode(2),
              "present.bag' exists; pass --overwrite to replace it");
  EXPECT_EQ(writer({"--output", present, "--overwrite"}), std::make_pair(present, true));
  EXPECT_TRUE(fs::exists(present)) << "parse() only checks; it never removes a file";
  EXPECT_EXIT(writer({}), testing::ExitedWithCode(2), "--output is required");
}

// Runs `command`, returning its exit status and what it printed (stdout and stderr).
int run(const std::string& command, std::string* output) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((command + " 2>&1").c_str(), "r"), pclose);
  std::array<char, 4096> buf{};
  output->clear();
  for (size_t n; (n = fread(buf.data(), 1, buf.size(), pipe.get())) > 0;)
    output->append(buf.data(), n);
  const int status = pclose(pipe.release());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Tools, EveryToolAnswersHelpAndRefusesAnUnknownOption) {
  // demo_monitor and lockstep_player are ROS nodes (their settings are parameters);
  // bench_ekf_slam takes Google Benchmark's own flags; command_line is CommandLine itself.
  const std::vector<std::string> not_command_line = {"demo_monitor", "lockstep_player",
                                                     "bench_ekf_slam", "command_line"};
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(AP_SOURCE_DIR) / "src/tools")) {
    if (entry.path().extension() != ".cpp") continue;
    const std::string tool = entry.path().stem().string();
    if (std::find(not_command_line.begin(), not_command_line.end(), tool) != not_command_line.end())
      continue;
    const fs::path binary = fs::path(AP_TOOL_DIR) / tool;
    if (!fs::exists(binary)) {
      // Only the benchmarks may be missing (Google Benchmark not installed).
      EXPECT_EQ(tool.rfind("bench_", 0), 0u) << binary << " was not built";
      continue;
    }
    std::string out;
    EXPECT_EQ(run(binary.string() + " --help", &out), 0) << tool << ":\n" << out;
    EXPECT_NE(out.find("Usage: " + tool), std::string::npos) << tool << ":\n" << out;
    EXPECT_NE(out.find("Options:"), std::string::npos) << tool << ":\n" << out;
    EXPECT_EQ(run(binary.string() + " --no_such_option 1", &out), 2) << tool << ":\n" << out;
    EXPECT_NE(out.find("no_such_option"), std::string::npos) << tool << ":\n" << out;
    ++checked;
  }
  EXPECT_GE(checked, 15);
}

// field_images_to_bag reads and checks every image of the list before it opens the bag: a bad line
// is named with its file and line, and no bag (nor its temporary) is left behind.
TEST(Tools, FieldImagesToBagChecksEveryImageBeforeWriting) {
  ScratchDir dir("field_images_to_bag");
  const fs::path good = dir.path() / "good.png", small = dir.path() / "small.png",
                 text = dir.path() / "text.jpg", bag = dir.path() / "out.bag";
  ASSERT_TRUE(cv::imwrite(good.string(), cv::Mat(480, 640, CV_8UC3, cv::Scalar(40, 120, 40))));
  ASSERT_TRUE(cv::imwrite(small.string(), cv::Mat(240, 320, CV_8UC3, cv::Scalar(40, 120, 40))));
  std::ofstream(text) << "not an image";
  const auto list = [&](const std::string& name, const std::vector<std::string>& lines) {
    const fs::path p = dir.path() / name;
    std::ofstream out(p);
    out << "image,head_pitch_rad,head_yaw_rad\n";
    for (const std::string& l : lines) out << l << "\n";
    return p.string();
  };
  const std::string tool = std::string(AP_TOOL_DIR) + "/field_images_to_bag --camera " +
                           AP_SOURCE_DIR + "/config/cameras/nao_v6_top.yaml --output " +
                           bag.string() + " --seconds_per_image 1 --rate_hz 5 --list ";
  std::string out;
  EXPECT_EQ(run(tool + list("small.csv", {"good.png,0.0,0.0", "small.png,0.0,0.0"}), &out), 1);
  EXPECT_NE(out.find("small.csv:3: "), std::string::npos) << out;
  EXPECT_NE(out.find("is 320x240 but the camera (nao_v6_top) is 640x480"), std::string::npos)
      << out;
  EXPECT_EQ(run(tool + list("text.csv", {"text.jpg,0.0,0.0"}), &out), 1);
  EXPECT_NE(out.find("text.csv:2: "), std::string::npos) << out;
  EXPECT_NE(out.find("not a JPEG or PNG file"), std::string::npos) << out;
  EXPECT_EQ(run(tool + list("pitch.csv", {"good.png,1.5,0.0"}), &out), 1);
  EXPECT_NE(out.find("pitch.csv:2: head angles"), std::string::npos) << out;
  EXPECT_NE(out.find("outside the joint ranges of nao_v6_top"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(bag));
  // Nor its temporary (`.NAME.XXXXXX` beside it, ros/bag_writer.h).
  for (const auto& e : fs::directory_iterator(bag.parent_path()))
    EXPECT_NE(e.path().filename().string().rfind("." + bag.filename().string() + ".", 0), 0u)
        << e.path();
  // Two images, one second each at 5 Hz.
  EXPECT_EQ(run(tool + list("ok.csv", {"good.png,0.0,0.0", "good.png,0.1,-0.2"}), &out), 0)
      << out;
  EXPECT_NE(out.find("images=2 frames=10 duration_s=2.0"), std::string::npos) << out;
  EXPECT_TRUE(fs::exists(bag));
}

// simulate_tracking --video writes the video to a temporary of a unique name beside it and renames
// it when complete: a user's file named as the old fixed temporary (VIDEO.tmp.avi) is left alone.
TEST(Tools, SimulateTrackingVideoLeavesAUsersFilesAlone) {
  ScratchDir dir("simulate_tracking_video");
  const fs::path video = dir.path() / "clip.avi", mine = dir.path() / "clip.avi.tmp.avi";
  std::ofstream(mine) << "the user's own file\n";
  std::string out;
  const std::string tool = std::string(AP_TOOL_DIR) + "/simulate_tracking --frames 5 --video ";
  ASSERT_EQ(run(tool + video.string(), &out), 0) << out;
  EXPECT_GT(fs::file_size(video), 0u);
  EXPECT_TRUE(fs::exists(dir.path() / "clip.csv"));
  std::ifstream in(mine);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "the user's own file");
  // Nothing else beside them: no temporary left.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), {}), 3);
}

// evaluate_color_priors names an image that has no mask, before any work.
TEST(Tools, EvaluateColorPriorsNamesAnImageWithoutAMask) {
  ScratchDir dir("evaluate_color_priors");
  fs::create_directories(dir.path() / "image");
  fs::create_directories(dir.path() / "mask");
  const cv::Mat image(48, 64, CV_8UC3, cv::Scalar(40, 120, 40));
  cv::Mat mask(48, 64, CV_8UC1, cv::Scalar(3));
  mask.rowRange(20, 24).setTo(2);
  for (const std::string name : {"a", "b", "c"}) {
    ASSERT_TRUE(cv::imwrite((dir.path() / "image" / (name + ".png")).string(), image));
    if (name != "b") {
      ASSERT_TRUE(cv::imwrite((dir.path() / "mask" / (name + ".png")).string(), mask));
    }
  }
  std::string out;
  EXPECT_EQ(run(std::string(AP_TOOL_DIR) + "/evaluate_color_priors --images " +
                    (dir.path() / "image").string() + " --masks " +
                    (dir.path() / "mask").string() + " --output " +
                    (dir.path() / "results").string(),
                &out),
            1);
  EXPECT_NE(out.find("b.png"), std::string::npos) << out;
  EXPECT_NE(out.find("mask"), std::string::npos) << out;
}

}  // namespace
