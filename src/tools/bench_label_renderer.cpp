// bench_label_renderer: throughput of the label renderer on one core, on a fixed set of camera
// poses drawn from the head chain over the whole field (seeded, so every run renders the same
// views).
//
//   bench_label_renderer --help   (every option with its default, unit and range)
//
// Last line: `bench_label_renderer: labeled_pixels_per_s=... full_frame_pixels_per_s=...
// subsample_pixels_per_s=... frames_per_s=...` (full frames of 208x160, and the particle filter's
// case: a 1-in-16 pixel subsample per pose).
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/world/label_renderer.h"
#include "bench_timing.h"
#include "command_line.h"

using namespace adaptive_perception;

int main(int argc, char** argv) {
  tools::CommandLine cli("bench_label_renderer",
                         "Throughput of the label renderer on one core, on a fixed seeded set of "
                         "camera poses over the whole field.");
  std::string field;
  cli.option("field", &field, "field description (YAML; empty: the built-in 4-legged league field)");
  int n_poses = 2000;
  cli.option("poses", &n_poses, config::closed(1, 1000000), "camera poses");
  const double& seconds = cli.measurementSeconds(2.0);
  const std::uint64_t& seed = cli.seed();
  cli.parse(argc, argv);

  const world::FieldMap map = field.empty() ? world::FieldMap() : world::FieldMap::loadYaml(field);
  const world::PinholeCamera cam = world::PinholeCamera::aiboErs7();
  const world::LabelRenderer renderer(map, cam);
  const world::HeadChain head;
  math::Rng rng(seed);
  std::vector<Eigen::Isometry3d> poses;
  while (static_cast<int>(poses.size()) < n_poses) {
    const double x = rng.uniform(-2.9, 2.9), y = rng.uniform(-1.9, 1.9);
    if (!map.isFree(x, y, 0.15)) continue;
    const math::SE2 base(x, y, rng.uniform(-math::kPi, math::kPi));
    const double tilt = rng.uniform(-0.2, 0.7), pan = rng.uniform(-1.5, 1.5);
    poses.push_back(world::planarToIsometry(base) * head.baseToOptical(pan, tilt));
  }
  std::vector<world::PixelCoord> subsample;
  for (int v = 0; v < cam.height_px; v += 4)
    for (int u = (v / 4) % 4; u < cam.width_px; u += 4)
      subsample.push_back({static_cast<std::uint16_t>(u), static_cast<std::uint16_t>(v)});

  std::vector<std::uint8_t> labels(cam.width_px * cam.height_px);
  unsigned checksum = 0;
  auto run = [&](bool full) {
    long pixels = 0;
    long frames = 0;
    const double frames_per_s = tools::unitsPerSecond(seconds, [&] {
      for (int i = 0; i < 100; ++i) {
        const auto& pose = poses[frames % poses.size()];
        if (full) {
          renderer.renderImage(pose, labels.data());
          pixels += static_cast<long>(labels.size());
        } else {
          renderer.renderPixels(pose, subsample.data(), subsample.size(), labels.data());
          pixels += static_cast<long>(subsample.size());
        }
        checksum += labels[frames % subsample.size()];
        ++frames;
      }
      return 100;
    });
    return std::make_pair(frames_per_s * pixels / frames, frames_per_s);
  };
  const auto [full_px, full_fps] = run(true);
  const auto [sub_px, sub_fps] = run(false);
  std::printf("camera %dx%d, %d poses, %zu subsampled pixels per pose (checksum %u)\n",
              cam.width_px, cam.height_px, n_poses, subsample.size(), checksum);
  std::printf("full frames:  %.3g pixels/s, %.0f frames/s\n", full_px, full_fps);
  std::printf("subsample:    %.3g pixels/s, %.0f poses/s\n", sub_px, sub_fps);
  std::printf(
      "bench_label_renderer: labeled_pixels_per_s=%.0f full_frame_pixels_per_s=%.0f "
      "subsample_pixels_per_s=%.0f frames_per_s=%.0f\n",
      std::min(full_px, sub_px), full_px, sub_px, full_fps);
  return 0;
}
