// learn_tracking_dynamics: estimates the CONDENSATION dynamics A (A1, A0, d) and B of papers/001
// section 3.3 ("estimated a priori from a training sequence") from a sequence with ground truth.
//
//   learn_tracking_dynamics --help   (every option with its default, unit and range)
//
// Per frame the target's colour distribution is the colours inside the ellipse inscribed in its
// true box, shrunk to --inner of it (so little background gets in); its state is [centroid,
// principal magnitudes, the angles turning the previous frame's axes onto this frame's]. learnAr2
// (tracking/dynamics.h) fits x_t = A1 x_{t-1} + A0 x_{t-2} + d + B w per dimension (or with full
// matrices, --full). The YAML is written beside and renamed; an existing file is kept unless
// --overwrite. Last line: `learn_tracking_dynamics: frames=N output=FILE noise_sd=s1,..,s8`.
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "adaptive_perception/tracking/affine_snake.h"
#include "adaptive_perception/tracking/color_distribution.h"
#include "adaptive_perception/tracking/color_histogram.h"
#include "adaptive_perception/tracking/dynamics.h"
#include "command_line.h"
#include "tracking_sequence.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  tools::CommandLine cli("learn_tracking_dynamics",
                         "Estimates the CONDENSATION dynamics A (A1, A0, d) and B of papers/001 "
                         "section 3.3 from a sequence with ground truth.");
  tools::TrackingSource source;
  source.addOptions(cli);
  const std::string& output = cli.outputFile("the dynamics to write (YAML)", "the file");
  tracking::ColorSpace space = tracking::ColorSpace::kOpponent;
  cli.word("color_space", &space, tracking::colorSpaces(), "colour space of the histograms");
  bool full = false;
  cli.flag("full", &full, "fits full matrices (default: one AR(2) per dimension)");
  double inner = 0.6;
  cli.option("inner", &inner, config::aboveZero(1),
             "colours are taken inside the true box shrunk to this fraction");
  cli.parse(argc, argv);
  if (source.bag.empty() == source.video.empty())
    cli.fail("give exactly one of --bag FILE and --video FILE");
  source.findGroundTruth();
  try {
    std::vector<tracking::DistributionState> states;
    std::optional<tracking::ColorStats> previous;
    tools::forEachTrackingFrame(source, 0, [&](const tools::TrackingFrameIn& f) {
      if (!f.truth) return;
      const cv::Rect2d& b = *f.truth;
      const tracking::Contour ell = tracking::ellipseContour(
          b.x + b.width / 2, b.y + b.height / 2, inner * b.width / 2, inner * b.height / 2, 32);
      const cv::Rect box =
          cv::Rect(tracking::contourBox(ell)) & cv::Rect(0, 0, f.bgr.cols, f.bgr.rows);
      if (box.area() <= 0) return;
      const cv::Mat mask = tracking::contourMask(ell, box.size(), box.tl());
      tracking::ColorPoints pts;
      for (int y = 0; y < box.height; ++y)
        for (int x = 0; x < box.width; ++x)
          if (mask.at<uchar>(y, x))
            pts.push_back(tracking::toColorSpace(f.bgr.at<cv::Vec3b>(box.y + y, box.x + x), space));
      if (pts.size() < 10) return;
      const tracking::ColorStats s = tracking::colorStats(pts);
      tracking::DistributionState x = tracking::stateOf(s);
      if (previous) x.tail<2>() = tracking::alignmentAngles(previous->axes, s.axes);
      previous = s;
      states.push_back(x);
    });
    const tracking::Ar2Model m = tracking::learnAr2(states, !full);
    m.saveYaml(output);
    std::printf("learn_tracking_dynamics: frames=%zu output=%s noise_sd=", states.size(),
                output.c_str());
    for (int k = 0; k < tracking::kStateDim; ++k)
      std::printf("%s%.4f", k ? "," : "", std::sqrt((m.b * m.b.transpose())(k, k)));
    std::printf("\n");
  } catch (const std::exception& e) {
    std::cerr << "learn_tracking_dynamics: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
