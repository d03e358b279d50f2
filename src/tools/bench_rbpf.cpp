// bench_rbpf: frames per second of the Rao-Blackwellised localizer on a simulated sequence (the
// field simulator, seed 1, bright lighting), tracking from the true start pose. The camera is the
// AIBO ERS-7's field of view at --width x --height pixels (default its own 208x160; 640x480 is a
// NAO's image size): the same views with more pixels, the likelihood's strides scaled with the
// width (RbpfConfig::forCamera).
//
//   bench_rbpf --help   (every option with its default, unit and range)
//
// The relocalization check runs as rbpf_localizer's defaults have it (every 1 s); with
// --relocalization_interval_s S (0: off) a search of relocalization_pool_size uniform poses over 4
// images starts every S seconds of the sequence (no kidnap: a check that wins here is a false
// alarm, counted as `relocalizations`). The sequence runs at --rate_hz (10 by default; a NAO's
// camera gives 30): the check's cost is spread over the frames of its interval, so a frame rate is
// only meaningful at the rate the camera gives. --adapt_priors_to_image true runs the path a real
// camera takes (the priors adapted to the first image, and every image white-balanced by its
// paint unless --balance_to_paint false).
//
// Without --particles/--threads it sweeps 100, 300 and 1000 particles on 1 thread and on all cores.
// Last line: `bench_rbpf: frames_per_s=... (for the first configuration) ...` with one key per
// configuration: frames_per_s_<particles>_<threads>.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>

#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/localization/rbpf_localizer.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/sim/field_simulator.h"
#include "command_line.h"

using namespace adaptive_perception;

int main(int argc, char** argv) {
  tools::CommandLine cli("bench_rbpf",
                         "Frames per second of the Rao-Blackwellised localizer on a simulated "
                         "sequence (208x160 unless --width/--height); without --particles and "
                         "--threads it sweeps 100, "
                         "300 and 1000 particles on one thread and on all cores.");
  long particles = 0;
  cli.option("particles", &particles, config::closed(0, 100000), "particles (0: the sweep)");
  long threads = 0;
  cli.option("threads", &threads, config::closed(0, 256), "threads (0: the sweep)");
  int frames = 40;
  int width = 208, height = 160;
  cli.option("width", &width, config::closed(16, 4096), "image width, px");
  cli.option("height", &height, config::closed(16, 4096), "image height, px");
  cli.option("frames", &frames, config::closed(1, 100000), "frames of the sequence");
  double rate_hz = 10.0;
  cli.option("rate_hz", &rate_hz, config::closed(1.0, 1000.0),
             "the sequence's frame rate, Hz (the camera's)");
  localization::RbpfConfig base;  // these fields as rbpf_localizer's parameters, the rest default
  cli.fields(localization::RbpfConfig::fields(), &base,
             {"pixel_stride", "relocalization_interval_s", "relocalization_pool_size",
              "adapt_priors_to_image", "balance_to_paint"});
  cli.parse(argc, argv);
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::pair<int, int>> configs;
  if (particles > 0 || threads > 0) {
    configs.push_back({particles > 0 ? static_cast<int>(particles) : 100,
                       threads > 0 ? static_cast<int>(threads) : 1});
  } else {
    for (int n : {100, 300, 1000})
      for (int t : {1, cores}) configs.push_back({n, t});
  }
  const world::FieldMap map;
  constexpr double kDeg = M_PI / 180.0;
  const world::PinholeCamera cam =
      width == 208 && height == 160
          ? world::PinholeCamera::aiboErs7()
          : world::PinholeCamera::fromFieldOfView(width, height, 56.9 * kDeg, 45.2 * kDeg);
  const world::HeadChain head;
  const std::string dir = ros_params::resolvePackagePath("config/color_priors");
  const std::vector<color::LightingPrior> priors = {
      color::LightingPrior::loadYaml(dir + "/dark.yaml"),
      color::LightingPrior::loadYaml(dir + "/bright.yaml")};
  // The sequence, rendered once.
  sim::FieldSimConfig sc;
  sim::FieldSimulator simulator(map, cam, head, sc);
  const math::SE2 start = simulator.state().true_pose;
  std::vector<cv::Mat> images;
  std::vector<math::SE2> deltas;
  std::vector<Eigen::Isometry3d> heads;
  math::SE2 prev = simulator.state().odom_pose;
  for (int k = 0; k < frames; ++k) {
    simulator.advanceTo(k / rate_hz);
    images.push_back(color::unpackUyvy(simulator.renderCamera().uyvy));
    deltas.push_back(math::between(prev, simulator.state().odom_pose));
    heads.push_back(head.baseToOptical(simulator.state().pan_rad, simulator.state().tilt_rad));
    prev = simulator.state().odom_pose;
  }
  const math::SE2 end_truth = simulator.state().true_pose;
  std::string summary = "bench_rbpf:";
  bool first = true;
  for (const auto& [n, t] : configs) {
    localization::RbpfConfig cfg = base;
    cfg.particles = n;
    cfg.threads = t;
    localization::RbpfLocalizer rbpf(map, cam, priors, cfg);
    rbpf.initGaussian(start, Eigen::Vector3d(0.01, 0.01, 0.01).asDiagonal());
    const auto t0 = std::chrono::steady_clock::now();
    int flips = 0, relocalizations = 0, resamplings = 0;
    for (int k = 0; k < frames; ++k) {
      const auto r = rbpf.step(deltas[k], 1.0 / rate_hz, images[k], heads[k]);
      flips += r.mirror_flipped;
      relocalizations += r.relocalized;
      resamplings += r.resampled;
    }
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double fps = frames / s;
    const math::SE2 e = rbpf.estimate().pose;
    std::printf(
        "%5d particles, %d thread(s), %dx%d at %.0f Hz, stride %d (%zu pixels), relocalization "
        "check every %.1f s over %d poses: %.1f frames/s (final position error %.3f m, mirror "
        "flips %d, relocalizations %d, resamplings %d)\n",
        n, t, width, height, rate_hz, rbpf.config().likelihood.pixel_stride, rbpf.pixels().size(),
        cfg.relocalization.interval_s, cfg.relocalization.pool_size, fps,
        std::hypot(e.x_m - end_truth.x_m, e.y_m - end_truth.y_m), flips, relocalizations,
        resamplings);
    char buf[96];
    if (first) {
      std::snprintf(buf, sizeof buf, " frames_per_s=%.1f", fps);
      summary += buf;
      first = false;
    }
    std::snprintf(buf, sizeof buf, " frames_per_s_%d_%d=%.1f", n, t, fps);
    summary += buf;
  }
  std::printf("%s\n", summary.c_str());
  return 0;
}
