// evaluate_lines: runs the line extractor over every scan of a bag. With ground_truth/walls
// (simulator bags) it scores the segments against the walls in view; on real logs (no truth) it
// reports speed. Either way it draws one scan with its segments (PNG).
//
//   evaluate_lines --help   (every option with its default, unit and range)
// --<field>: any of line_extractor's parameters (laser::LineExtractionConfig::fields(), the same
// names and ranges), e.g. --range_noise_std_m, the laser's range noise the extractor assumes.
//
// Scoring: laser/line_evaluation.h (wall pieces in view, matching within 0.1 m and 5 degrees).
// Writes OUTPUT/results.yaml, OUTPUT/scan.png. Last line:
//   evaluate_lines: precision=.. recall=.. mean_endpoint_error_m=.. mean_angle_error_deg=..
//   line_nees_mean=.. line_nees_in_bounds=.. scans_per_s=.. scans=N
// (line NEES: laser/line_evaluation.h; 2 and 0.95 when the fit covariance is right)
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/laser/line_evaluation.h"
#include "adaptive_perception/math/angles.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/params.h"
#include "command_line.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  tools::CommandLine cli("evaluate_lines",
                         "Runs the line extractor over every scan of a bag: scores the segments "
                         "against ground_truth/walls where the bag has them (simulator bags), "
                         "else reports speed; draws one scan with its segments.");
  const std::string& bag_path = cli.inputBag("laser bag");
  const std::string& output = cli.resultsFolder("results.yaml and scan.png");
  long plot_scan = -1;
  cli.option("plot_scan", &plot_scan, "index of the scan drawn (-1: the middle one)");
  // line_extractor's parameters (the same names and ranges), e.g. --range_noise_std_m.
  laser::LineExtractionConfig cfg;
  cli.fields(laser::LineExtractionConfig::fields(), &cfg);
  cli.word("split_method", &cfg.split_method, laser::splitMethods(), "the split step");
  std::string name;
  cli.option("name", &name, "label of the run (empty: the bag's file name)");
  bool no_plot = false;
  cli.flag("no_plot", &no_plot, "skip the drawing");
  cli.parse(argc, argv);
  if (name.empty()) name = fs::path(bag_path).stem().string();
  const bool plot = !no_plot;
  try {
    laser::LineExtractor extractor(cfg);
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    std::vector<sensor_msgs::LaserScanConstPtr> scans;
    std::map<ros::Time, LineSegmentArrayConstPtr> truth;
    for (const auto& m : rosbag::View(bag)) {
      if (m.getTopic() == "/scan" || m.getTopic() == "scan") {
        if (auto s = m.instantiate<sensor_msgs::LaserScan>()) scans.push_back(s);
      } else if (m.getTopic() == "/ground_truth/walls" || m.getTopic() == "ground_truth/walls") {
        if (auto w = m.instantiate<LineSegmentArray>()) truth[w->header.stamp] = w;
      }
    }
    if (scans.empty()) throw std::runtime_error(bag_path + ": no scan messages");
    // Speed: extraction alone over the whole bag.
    std::vector<laser::LaserScan2D> core_scans;
    for (const auto& s : scans) core_scans.push_back(ros_conv::fromLaserScan(*s));
    const auto t0 = std::chrono::steady_clock::now();
    long segs_total = 0;
    for (const auto& s : core_scans) segs_total += static_cast<long>(extractor.extract(s).size());
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double scans_per_s = core_scans.size() / std::max(secs, 1e-9);

    laser::LineScore score;
    for (size_t i = 0; i < core_scans.size(); ++i) {
      auto it = truth.find(scans[i]->header.stamp);
      if (it == truth.end()) continue;
      score.add(laser::scoreSegments(extractor.extract(core_scans[i]),
                                     ros_conv::wallPieces(*it->second), cfg));
    }
    fs::create_directories(output);
    // One scan and its segments for the plot.
    const size_t shown =
        plot_scan >= 0 ? std::min<size_t>(plot_scan, scans.size() - 1) : scans.size() / 2;
    {
      std::ofstream pts(fs::path(output) / "scan_points.csv"),
          sg(fs::path(output) / "scan_segments.csv");
      pts << "x,y\n";
      std::vector<laser::ScanPoint> valid;
      laser::validPoints(core_scans[shown], cfg.min_range_m, &valid);
      for (const auto& p : valid) pts << p.p_m.x() << "," << p.p_m.y() << "\n";
      sg << "x0,y0,x1,y1\n";
      for (const auto& s : extractor.extract(core_scans[shown]))
        sg << s.start_m.x() << "," << s.start_m.y() << "," << s.end_m.x() << "," << s.end_m.y()
           << "\n";
    }
    const bool has_truth = !truth.empty();
    std::ofstream yaml(fs::path(output) / "results.yaml");
    yaml << "bag: " << bag_path << "\nname: " << name
         << "\nsplit_method: " << laser::splitMethods().name(cfg.split_method)
         << "\nscans: " << scans.size()
         << "\nsegments_per_scan: " << double(segs_total) / scans.size()
         << "\nscans_per_s: " << scans_per_s << "\n";
    if (has_truth)
      yaml << "precision: " << score.precision() << "\nrecall: " << score.recall()
           << "\nmean_endpoint_error_m: " << score.meanEndpointError()
           << "\nmean_angle_error_deg: " << math::radToDeg(score.meanAngleErrorRad())
           << "\nline_nees_mean: " << score.meanLineNees()
           << "\nline_nees_in_bounds: " << score.lineNeesInBounds()
           << "\nwalls_scored: " << score.truth_eligible << "\nsegments_scored: " << score.extracted
           << "\n";
    yaml.close();
    if (plot) {
      const std::string script = ros_params::resolvePackagePath("scripts/plot_scan_lines.py");
      const std::string cmd = "PATH=/usr/bin:$PATH python3 '" + script + "' '" + output + "' '" +
                              name + ", scan " + std::to_string(shown) + "' > /dev/null 2>&1";
      if (std::system(cmd.c_str()) != 0)
        std::fprintf(stderr, "evaluate_lines: warning: plot failed (%s)\n", cmd.c_str());
    }
    if (has_truth) {
      std::printf(
          "evaluate_lines: precision=%.3f recall=%.3f mean_endpoint_error_m=%.3f "
          "mean_angle_error_deg=%.2f line_nees_mean=%.2f line_nees_in_bounds=%.3f "
          "scans_per_s=%.0f scans=%zu\n",
          score.precision(), score.recall(), score.meanEndpointError(),
          math::radToDeg(score.meanAngleErrorRad()), score.meanLineNees(), score.lineNeesInBounds(),
          scans_per_s, scans.size());
    } else {
      std::printf(
          "evaluate_lines: scans_per_s=%.0f segments_per_scan=%.1f scans=%zu (no ground truth)\n",
          scans_per_s, double(segs_total) / scans.size(), scans.size());
    }
  } catch (const std::exception& e) {
    std::cerr << "evaluate_lines: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
