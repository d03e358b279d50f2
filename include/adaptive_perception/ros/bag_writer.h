#pragma once
// Writing a bag the safe way for the tools: to a new file of a unique name beside FILE
// (io::createTemporaryBeside: `.FILE.XXXXXX`, so a user's own FILE.tmp, or a symlink of that name,
// is never touched, and two runs writing the same FILE do not write into each other), renamed over
// FILE only when complete (a failed run leaves the user's FILE untouched and removes the
// temporary), lz4 by default, and
// latched topics (tf_static) written with the connection header that makes `rosbag play` latch
// them.
#include <ros/message_traits.h>
#include <rosbag/bag.h>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "adaptive_perception/io/atomic_file.h"

namespace adaptive_perception::ros_bag {

class BagWriter {
 public:
  /// Throws std::runtime_error when `path` exists and `overwrite` is false, or it cannot be
  /// written.
  BagWriter(const std::string& path, bool overwrite, bool compress = true)
      : path_(path) {
    if (std::filesystem::exists(path) && !overwrite)
      throw std::runtime_error("'" + path + "' exists; pass --overwrite to replace it");
    tmp_ = io::createTemporaryBeside(path);
    try {
      bag_.open(tmp_, rosbag::bagmode::Write);
    } catch (...) {
      std::error_code ec;
      std::filesystem::remove(tmp_, ec);
      throw;
    }
    if (compress) bag_.setCompression(rosbag::compression::LZ4);
  }
  ~BagWriter() {
    if (!closed_) {
      bag_.close();
      std::error_code ec;
      std::filesystem::remove(tmp_, ec);
    }
  }
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  template <typename Msg>
  void write(const std::string& topic, const ros::Time& t, const Msg& msg) {
    bag_.write(topic, t, msg);
  }
  /// A latched message (e.g. tf_static): its connection header carries latching=1 (and, as rosbag
  /// then uses it verbatim, the type fields).
  template <typename Msg>
  void writeLatched(const std::string& topic, const ros::Time& t, const Msg& msg,
                    const std::string& callerid) {
    auto header = boost::make_shared<ros::M_string>();
    (*header)["type"] = ros::message_traits::datatype<Msg>();
    (*header)["md5sum"] = ros::message_traits::md5sum<Msg>();
    (*header)["message_definition"] = ros::message_traits::definition<Msg>();
    (*header)["latching"] = "1";
    (*header)["callerid"] = callerid;
    bag_.write(topic, t, msg, header);
  }
  /// The temporary file the bag is written to until close().
  const std::string& temporaryPath() const { return tmp_; }
  /// Finishes the bag and moves it into place; returns its size in bytes.
  std::uintmax_t close() {
    closed_ = true;  // whatever happens below, the destructor has nothing left to close
    try {
      bag_.close();
      std::filesystem::rename(tmp_, path_);
    } catch (...) {
      std::error_code ec;
      std::filesystem::remove(tmp_, ec);
      throw;
    }
    return std::filesystem::file_size(path_);
  }

 private:
  std::string path_, tmp_;
  rosbag::Bag bag_;
  bool closed_ = false;
};

}  // namespace adaptive_perception::ros_bag
