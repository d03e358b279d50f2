// bench_tracker: frames per second of the trackers of papers/001 section 3 on one core.
//
//   bench_tracker --help   (every option with its default, unit and range)
//
// Frames come from the tracking simulator (sim/tracking_scene.h), rendered before timing. Times
// the CONDENSATION tracker with --samples samples and the elliptical head tracker alone, each over
// the same frames from the first frame's ground truth, with OpenCV on one thread. The paper ran in
// MATLAB and gave no speed; the target is 30 frames per second at 320 x 240 with 100 samples.
// Also times the box tracker (tracking/box_condensation_tracker.h: the default tracker of
// evaluate_tracking and of the node) with its default configuration (or the --box_* options given);
// its target is 30 frames per
// second at 640 x 480 and 100 at 320 x 240. Last line: `bench_tracker: fps=.. ms_per_frame=..
// condensation_fps=.. condensation_ms_per_frame=.. ellipse_fps=.. samples=N width=W height=H
// lost_frames=L` (fps and ms_per_frame: the box tracker; samples and lost_frames: CONDENSATION's).
#include <chrono>
#include <cstdio>
#include <iostream>
#include <opencv2/core/utility.hpp>

#include "adaptive_perception/sim/tracking_scene.h"
#include "adaptive_perception/tracking/box_condensation_tracker.h"
#include "adaptive_perception/tracking/condensation_tracker.h"
#include "adaptive_perception/tracking/ellipse_tracker.h"
#include "command_line.h"

using namespace adaptive_perception;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  tools::CommandLine cli("bench_tracker",
                         "Frames per second of the box, CONDENSATION and elliptical head trackers "
                         "on one core, on frames of the tracking simulator.");
  long samples = 100;
  cli.option("samples", &samples, config::closed(1, 100000), "CONDENSATION samples");
  sim::TrackingSceneConfig sc;
  sc.frames = 200;
  cli.fields(sim::TrackingSceneConfig::fields(), &sc, {"frames", "width", "height"});
  cli.word("scenario", &sc.scenario, sim::trackingScenarios(), "the simulated scene");
  tracking::BoxTrackerConfig bc;  // the box tracker's options, as the node's (e.g. --box_samples)
  cli.fields(tracking::BoxTrackerConfig::fields(), &bc);
  const std::uint64_t& seed = cli.seed();
  cli.parse(argc, argv);
  cv::setNumThreads(1);  // one core, as the target says
  try {
    sc.validate();
    tracking::CondensationConfig cc;
    cc.samples = static_cast<int>(samples);
    cc.validate();
    sim::TrackingScene scene(sc, seed);
    std::vector<sim::SceneFrame> frames;
    while (!scene.done()) frames.push_back(scene.next());

    tracking::CondensationTracker cond(cc, seed);
    cond.init(frames[0].bgr, cv::Rect(frames[0].truth));
    long lost = 0;
    auto t0 = Clock::now();
    for (size_t i = 1; i < frames.size(); ++i) lost += cond.track(frames[i].bgr).lost;
    const double cond_s = std::chrono::duration<double>(Clock::now() - t0).count();

    tracking::EllipseTracker ell;
    ell.init(frames[0].bgr, tracking::Ellipse::inscribed(frames[0].truth));
    t0 = Clock::now();
    for (size_t i = 1; i < frames.size(); ++i) ell.track(frames[i].bgr);
    const double ell_s = std::chrono::duration<double>(Clock::now() - t0).count();

    tracking::BoxCondensationTracker box(bc, seed);
    box.init(frames[0].bgr, frames[0].truth);
    t0 = Clock::now();
    for (size_t i = 1; i < frames.size(); ++i) box.track(frames[i].bgr);
    const double box_s = std::chrono::duration<double>(Clock::now() - t0).count();

    const double n = static_cast<double>(frames.size() - 1);
    std::printf(
        "bench_tracker: fps=%.1f ms_per_frame=%.2f condensation_fps=%.1f "
        "condensation_ms_per_frame=%.2f ellipse_fps=%.1f samples=%ld width=%d height=%d "
        "lost_frames=%ld\n",
        n / box_s, 1e3 * box_s / n, n / cond_s, 1e3 * cond_s / n, n / ell_s, samples, sc.width,
        sc.height, lost);
  } catch (const std::exception& e) {
    std::cerr << "bench_tracker: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
