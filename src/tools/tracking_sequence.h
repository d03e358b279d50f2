#pragma once
// Tracking sequences for the tracking tools (simulate_tracking writes them; evaluate_tracking and
// bench_tracker read them): a bag (camera/image_raw with ground_truth/box, a PolygonStamped of the
// box's 4 corners at the image's stamp) or a video file (anything cv::VideoCapture opens) with an
// optional ground-truth CSV `frame,x,y,w,h` (frame counted from 0; frames without a row have no
// truth).
#include <geometry_msgs/PolygonStamped.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/topics.h"
#include "command_line.h"

namespace adaptive_perception::tools {

/// A tracking sequence named on a command line: --bag FILE, or --video FILE with its ground truth
/// (--ground_truth CSV, by default the CSV of the same name beside the video when there is one).
struct TrackingSource {
  std::string bag, video, ground_truth;

  void addOptions(CommandLine& cli) {
    cli.option("bag", &bag, "tracking bag (simulate_tracking)");
    cli.option("video", &video, "video file");
    cli.option("ground_truth", &ground_truth,
               "the video's ground truth (CSV; empty: the CSV of the same name beside it)");
  }
  /// After parsing: the video's ground truth beside it, when none was named.
  void findGroundTruth() {
    if (video.empty() || !ground_truth.empty()) return;
    const std::filesystem::path beside = std::filesystem::path(video).replace_extension(".csv");
    if (std::filesystem::exists(beside)) ground_truth = beside.string();
  }
  /// The sequence's name: the file's stem.
  std::string name() const {
    return std::filesystem::path(bag.empty() ? video : bag).stem().string();
  }
};

struct TrackingFrameIn {
  int index = 0;
  double stamp_s = 0.0;
  cv::Mat bgr;
  std::optional<cv::Rect2d> truth;
};

/// Reads `frame,x,y,w,h` rows (a header line is allowed). Throws std::runtime_error naming the
/// file and line of a bad row.
inline std::map<int, cv::Rect2d> readGroundTruthCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the ground-truth CSV");
  std::map<int, cv::Rect2d> out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#' || (n == 1 && line.rfind("frame", 0) == 0)) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    int f;
    double x, y, w, h;
    if (!(s >> f >> x >> y >> w >> h) || f < 0 || !(w >= 0) || !(h >= 0))
      throw std::runtime_error(path + ":" + std::to_string(n) +
                               ": expected frame,x,y,w,h with frame >= 0 and w, h >= 0");
    out[f] = {x, y, w, h};
  }
  return out;
}

/// Calls `fn` per frame in order (at most `max_frames` when > 0); returns the count. Throws
/// std::runtime_error when the input cannot be opened.
inline int forEachTrackingFrame(const TrackingSource& source, int max_frames,
                                const std::function<void(const TrackingFrameIn&)>& fn) {
  const std::string& bag_path = source.bag;
  const std::string& video_path = source.video;
  const std::string& truth_csv = source.ground_truth;
  int n = 0;
  if (!bag_path.empty()) {
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    const std::string image_topic = std::string("/") + ros_topics::kCameraImage;
    const std::string box_topic = std::string("/") + ros_topics::kGroundTruthBox;
    std::map<std::int64_t, cv::Rect2d> boxes;
    rosbag::View bv(bag, rosbag::TopicQuery(std::vector<std::string>{box_topic}));
    for (const rosbag::MessageInstance& m : bv)
      if (const auto p = m.instantiate<geometry_msgs::PolygonStamped>())
        boxes[p->header.stamp.toNSec()] = ros_conv::polygonBox(p->polygon);
    rosbag::View v(bag, rosbag::TopicQuery(std::vector<std::string>{image_topic}));
    if (v.size() == 0) throw std::runtime_error(bag_path + ": no " + image_topic + " message");
    for (const rosbag::MessageInstance& m : v) {
      if (max_frames > 0 && n >= max_frames) break;
      const auto img = m.instantiate<sensor_msgs::Image>();
      if (!img) continue;
      TrackingFrameIn f;
      f.index = n;
      f.stamp_s = img->header.stamp.toSec();
      f.bgr = ros_conv::imageToBgr8(*img);
      const auto it = boxes.find(img->header.stamp.toNSec());
      if (it != boxes.end()) f.truth = it->second;
      fn(f);
      ++n;
    }
    return n;
  }
  cv::VideoCapture cap(video_path);
  if (!cap.isOpened()) throw std::runtime_error(video_path + ": cannot open the video");
  const std::map<int, cv::Rect2d> truth =
      truth_csv.empty() ? std::map<int, cv::Rect2d>{} : readGroundTruthCsv(truth_csv);
  double fps = cap.get(cv::CAP_PROP_FPS);
  if (!(fps > 0)) fps = 30.0;
  cv::Mat frame;
  while ((max_frames <= 0 || n < max_frames) && cap.read(frame)) {
    TrackingFrameIn f;
    f.index = n;
    f.stamp_s = n / fps;
    if (frame.type() == CV_8UC1)
      cv::cvtColor(frame, f.bgr, cv::COLOR_GRAY2BGR);
    else
      f.bgr = frame.clone();
    const auto it = truth.find(n);
    if (it != truth.end()) f.truth = it->second;
    fn(f);
    ++n;
  }
  if (n == 0) throw std::runtime_error(video_path + ": no frame could be read");
  return n;
}

}  // namespace adaptive_perception::tools
