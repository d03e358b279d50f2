// bench_color_classifier: full-frame colour classification throughput on one core (208x160 by
// default), through the lookup table from packed UYVY as the node does, and the direct eq. (9)
// classifier for comparison; also the cost of rebuilding the table.
//
//   bench_color_classifier --help   (every option with its default, unit and range)
//
// Last line: `bench_color_classifier: frames_per_s=... direct_frames_per_s=... lut_build_ms=...`
#include <chrono>
#include <cstdio>
#include <iostream>

#include "adaptive_perception/color/color_lut.h"
#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/ros/bag_frames.h"
#include "adaptive_perception/ros/params.h"
#include "bench_timing.h"
#include "command_line.h"

using namespace adaptive_perception;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  tools::CommandLine cli("bench_color_classifier",
                         "Full-frame colour classification throughput on one core, through the "
                         "lookup table and the direct classifier, and the table's rebuild cost.");
  std::string bag = "rosbag/field_bright.bag";
  cli.option("bag", &bag, "field bag whose images are classified (relative: from the package)");
  std::string prior_path = "config/color_priors/bright.yaml";
  cli.option("prior", &prior_path, "colour prior (YAML; relative: from the package)");
  const double& seconds = cli.measurementSeconds(2.0);
  cli.parse(argc, argv);
  bag = ros_params::resolvePackagePath(bag);
  prior_path = ros_params::resolvePackagePath(prior_path);
  try {
    const color::LightingPrior prior = color::LightingPrior::loadYaml(prior_path);
    const color::ColorFilter filter(prior, color::ColorModelConfig());
    const color::PixelClassifier cls = filter.classifier();
    ros_bag::BagFrameReader reader(bag);
    std::vector<cv::Mat> uyvy, yuv;
    for (const auto& f : reader.readAll()) {
      yuv.push_back(f.yuv);
      cv::Mat y, u, v, planes[3];
      cv::split(f.yuv, planes);
      planes[0].convertTo(y, CV_32F);
      planes[1].convertTo(u, CV_32F);
      planes[2].convertTo(v, CV_32F);
      uyvy.push_back(color::packUyvy(y, u, v));
    }
    if (uyvy.empty()) throw std::runtime_error(bag + ": no frames");
    color::ColorLut lut;
    const auto b0 = Clock::now();
    const int builds = 5;
    for (int i = 0; i < builds; ++i) lut.build(cls);
    const double build_ms =
        std::chrono::duration<double, std::milli>(Clock::now() - b0).count() / builds;

    cv::Mat labels;
    unsigned checksum = 0;
    long frames = 0;
    const double lut_fps = tools::unitsPerSecond(seconds, [&] {
      for (int i = 0; i < 200; ++i, ++frames) {
        lut.classifyUyvy(uyvy[frames % uyvy.size()], &labels);
        checksum += labels.data[frames % labels.total()];
      }
      return 200;
    });

    long direct_frames = 0;
    const double direct_fps = tools::unitsPerSecond(seconds, [&] {
      const cv::Mat& img = yuv[direct_frames++ % yuv.size()];
      for (int r = 0; r < img.rows; ++r)
        for (int c = 0; c < img.cols; ++c) {
          const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
          checksum += cls.classify(Eigen::Vector3d(p[0], p[1], p[2]));
        }
      return 1;
    });
    std::printf("image %dx%d, %zu distinct frames, checksum %u\n", uyvy[0].cols, uyvy[0].rows,
                uyvy.size(), checksum);
    std::printf("lookup table from UYVY: %.0f frames/s (%.3g pixels/s)\n", lut_fps,
                lut_fps * uyvy[0].total());
    std::printf("direct eq. (9):         %.0f frames/s\n", direct_fps);
    std::printf("table build:            %.2f ms\n", build_ms);
    std::printf(
        "bench_color_classifier: frames_per_s=%.0f direct_frames_per_s=%.0f lut_build_ms=%.2f\n",
        lut_fps, direct_fps, build_ms);
  } catch (const std::exception& e) {
    std::cerr << "bench_color_classifier: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
