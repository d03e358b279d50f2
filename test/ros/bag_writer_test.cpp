// ros_bag::BagWriter against its header's contract: the bag is written to a new file of a unique
// name beside FILE and renamed over FILE when complete; a user's own FILE.tmp (or a symlink of that
// name) is never touched; two writers of the same FILE do not write into each other; a writer
// that is not closed leaves nothing behind and FILE as it was.
#include "adaptive_perception/ros/bag_writer.h"

#include <gtest/gtest.h>
#include <rosbag/view.h>
#include <std_msgs/String.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "../core/scratch_dir.h"

namespace fs = std::filesystem;
using adaptive_perception::ros_bag::BagWriter;

namespace {

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std_msgs::String text(const std::string& s) {
  std_msgs::String m;
  m.data = s;
  return m;
}

// The strings on `topic` in the bag at `path`.
std::vector<std::string> strings(const fs::path& path) {
  rosbag::Bag bag(path.string(), rosbag::bagmode::Read);
  std::vector<std::string> out;
  for (const auto& m : rosbag::View(bag))
    if (auto s = m.instantiate<std_msgs::String>()) out.push_back(s->data);
  return out;
}

size_t entries(const fs::path& dir) {
  return static_cast<size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

}  // namespace

TEST(BagWriter, LeavesAUsersTmpFileAndASymlinkOfThatNameAlone) {
  const adaptive_perception::test_support::ScratchDir scratch("bag_writer");
  const fs::path dir = scratch.path();
  const fs::path bag = dir / "out.bag";
  std::ofstream(dir / "out.bag.tmp") << "the user's own notes";
  std::ofstream(dir / "elsewhere.txt") << "a file a symlink points at";
  const fs::path other = dir / "other.bag";
  fs::create_symlink(dir / "elsewhere.txt", dir / "other.bag.tmp");
  for (const fs::path& p : {bag, other}) {
    BagWriter w(p.string(), false);
    EXPECT_NE(w.temporaryPath(), p.string() + ".tmp");
    EXPECT_EQ(fs::path(w.temporaryPath()).parent_path(), dir);
    w.write("chatter", ros::Time(1.0), text("hello"));
    w.close();
    EXPECT_EQ(strings(p), std::vector<std::string>{"hello"});
  }
  EXPECT_EQ(readText(dir / "out.bag.tmp"), "the user's own notes");
  EXPECT_EQ(readText(dir / "elsewhere.txt"), "a file a symlink points at");
  EXPECT_TRUE(fs::is_symlink(dir / "other.bag.tmp"));
  EXPECT_EQ(entries(dir), 5u);  // the two bags, the notes, the symlink and its target
}

TEST(BagWriter, TwoWritersOfOneFileDoNotWriteIntoEachOther) {
  const adaptive_perception::test_support::ScratchDir scratch("bag_writer");
  const fs::path dir = scratch.path();
  const fs::path bag = dir / "out.bag";
  {
    BagWriter a(bag.string(), true), b(bag.string(), true);
    EXPECT_NE(a.temporaryPath(), b.temporaryPath());
    a.write("chatter", ros::Time(1.0), text("from a"));
    b.write("chatter", ros::Time(1.0), text("from b"));
    b.write("chatter", ros::Time(2.0), text("from b again"));
    a.close();
    EXPECT_EQ(strings(bag), std::vector<std::string>{"from a"});
    b.close();
  }
  EXPECT_EQ(strings(bag), (std::vector<std::string>{"from b", "from b again"}));
  EXPECT_EQ(entries(dir), 1u);
}

TEST(BagWriter, AWriterNotClosedLeavesNothingAndTheOldFileAsItWas) {
  const adaptive_perception::test_support::ScratchDir scratch("bag_writer");
  const fs::path dir = scratch.path();
  const fs::path bag = dir / "out.bag";
  {
    BagWriter w(bag.string(), false);
    w.write("chatter", ros::Time(1.0), text("kept"));
    w.close();
  }
  {
    BagWriter w(bag.string(), true);
    w.write("chatter", ros::Time(1.0), text("abandoned"));
  }  // e.g. the tool failed half way
  EXPECT_EQ(strings(bag), std::vector<std::string>{"kept"});
  EXPECT_EQ(entries(dir), 1u);
  EXPECT_THROW(BagWriter(bag.string(), false), std::runtime_error);  // exists, no overwrite
  EXPECT_THROW(BagWriter((dir / "no_such_folder" / "x.bag").string(), true), std::runtime_error);
  EXPECT_EQ(entries(dir), 1u);
}
