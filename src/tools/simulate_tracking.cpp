// simulate_tracking: the synthetic tracking sequences of papers/001 section 3.4 with ground
// truth (sim/tracking_scene.h).
//
//   simulate_tracking --help   (every option with its default, unit and range)
//
// A bag holds camera/image_raw (bgr8 unless --encoding) and ground_truth/box (PolygonStamped, the 4
// corners of the target's box, same stamp). A video is Motion-JPEG AVI (OpenCV's own writer, no
// codec needed) with a CSV `frame,x,y,w,h` (default: the video's path with .csv). Existing outputs
// are kept unless --overwrite. Last line: `simulate_tracking: scenario=S frames=N output=PATH`.
#include <geometry_msgs/PolygonStamped.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>

#include "adaptive_perception/io/atomic_file.h"
#include "adaptive_perception/ros/bag_writer.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/topics.h"
#include "adaptive_perception/sim/tracking_scene.h"
#include "command_line.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  tools::CommandLine cli("simulate_tracking",
                         "The synthetic tracking sequences of papers/001 section 3.4 with ground "
                         "truth, written to a bag or a video with a CSV.");
  sim::TrackingSceneConfig cfg;
  cli.word("scenario", &cfg.scenario, sim::trackingScenarios(), "the scene (papers/001 3.4)");
  const std::uint64_t& seed = cli.seed();
  cli.fields(sim::TrackingSceneConfig::fields(), &cfg);
  bool no_clutter = false;
  cli.flag("no_clutter", &no_clutter, "a plain background");
  std::string output;
  cli.option("output", &output, "the bag to write");
  std::string encoding = "bgr8";
  cli.option("encoding", &encoding, "the bag's image encoding")
      ->oneOf({"bgr8", "rgb8", "mono8"});
  std::string video;
  cli.option("video", &video, "the video to write (instead of a bag)");
  std::string truth_csv;
  cli.option("ground_truth", &truth_csv, "the video's ground truth (empty: beside it, .csv)");
  const bool& overwrite = cli.overwrite("the bag, video or CSV");
  cli.parse(argc, argv);
  cfg.clutter = !no_clutter;
  if (output.empty() == video.empty())
    cli.fail("give exactly one of --output FILE.bag and --video FILE");
  if (!video.empty() && truth_csv.empty())
    truth_csv = fs::path(video).replace_extension(".csv").string();
  for (const std::string& p : {output, video, truth_csv})
    if (!p.empty()) cli.refuseExisting(p);
  try {
    cfg.validate();
  } catch (const std::invalid_argument& e) {
    cli.fail(e.what());
  }
  std::string video_tmp;  // the video's temporary while it is written
  try {
    sim::TrackingScene scene(cfg, seed);
    std::unique_ptr<ros_bag::BagWriter> bag;
    std::unique_ptr<cv::VideoWriter> writer;
    std::ostringstream csv;  // written atomically at the end (io::writeTextFileAtomically)
    if (!output.empty()) bag = std::make_unique<ros_bag::BagWriter>(output, overwrite);
    if (!video.empty()) {
      // The ground truth's folder is writable (checked now, not after the whole video).
      fs::remove(io::createTemporaryBeside(truth_csv));
      // A new file of a unique name beside the video (the writer takes the container from its
      // extension), renamed over it when complete: nothing of the user's is touched on a failure.
      video_tmp = io::createTemporaryBeside(video, ".avi");
      writer = std::make_unique<cv::VideoWriter>(video_tmp, cv::CAP_OPENCV_MJPEG,
                                                 cv::VideoWriter::fourcc('M', 'J', 'P', 'G'),
                                                 cfg.rate_hz, cv::Size(cfg.width, cfg.height));
      if (!writer->isOpened()) throw std::runtime_error(video + ": cannot write the video");
      csv << "frame,x,y,w,h\n";
    }
    const ros::Time t0(1.6e9);
    while (!scene.done()) {
      const int k = scene.index();
      const sim::SceneFrame f = scene.next();
      const ros::Time stamp = t0 + ros::Duration(k / cfg.rate_hz);
      if (bag) {
        std_msgs::Header h;
        h.stamp = stamp;
        h.seq = static_cast<std::uint32_t>(k);
        h.frame_id = ros_topics::kCameraOpticalFrame;
        sensor_msgs::Image image;
        if (encoding == "mono8") {
          cv::Mat grey;
          cv::cvtColor(f.bgr, grey, cv::COLOR_BGR2GRAY);
          image = ros_conv::mono8ToImage(grey, h);
        } else if (encoding == "rgb8") {
          cv::Mat rgb;
          cv::cvtColor(f.bgr, rgb, cv::COLOR_BGR2RGB);
          image = ros_conv::bgr8ToImage(rgb, h);
          image.encoding = "rgb8";
        } else {
          image = ros_conv::bgr8ToImage(f.bgr, h);
        }
        bag->write("/" + std::string(ros_topics::kCameraImage), stamp, image);
        geometry_msgs::PolygonStamped box;
        box.header = h;
        const cv::Rect2d& b = f.truth;
        for (const auto& [x, y] : {std::pair{b.x, b.y},
                                   {b.x + b.width, b.y},
                                   {b.x + b.width, b.y + b.height},
                                   {b.x, b.y + b.height}}) {
          geometry_msgs::Point32 p;
          p.x = static_cast<float>(x);
          p.y = static_cast<float>(y);
          box.polygon.points.push_back(p);
        }
        bag->write("/" + std::string(ros_topics::kGroundTruthBox), stamp, box);
      }
      if (writer) {
        writer->write(f.bgr);
        csv << k << "," << f.truth.x << "," << f.truth.y << "," << f.truth.width << ","
            << f.truth.height << "\n";
      }
    }
    if (bag) bag->close();
    if (writer) {
      writer->release();
      io::writeTextFileAtomically(truth_csv, csv.str());
      fs::rename(video_tmp, video);
      video_tmp.clear();
    }
    std::printf("simulate_tracking: scenario=%s frames=%d output=%s\n",
                sim::trackingScenarioName(cfg.scenario).c_str(), cfg.frames,
                (output.empty() ? video : output).c_str());
  } catch (const std::exception& e) {
    if (!video_tmp.empty()) {
      std::error_code ignored;
      fs::remove(video_tmp, ignored);
    }
    std::cerr << "simulate_tracking: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
