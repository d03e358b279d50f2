// bench_appearance: speed of SIFT room classification and appearance MCL on one core, with a
// training set the size of the paper's (1,700 frames) rendered from the indoor simulator.
//
//   bench_appearance --help   (every option with its default, unit and range)
//
// Training frames: a cloudy run of the indoor building at the camera rate that gives --frames
// images (309 x 240), their SIFT features indexed. Test: --test_frames images of another run; per
// frame SIFT extraction (and the line-structure descriptor when --structure_weight > 0), the
// indexed matcher (candidates verified, joined with the structural similarity) and one MCL step.
// The paper (papers/002) needed about 3 minutes per image for single-image classification over
// 1,690 frames and 56 minutes for a 960-frame sequence with 24 particles (3.5 s per frame).
// OpenCV runs single-threaded here. Last line: `bench_appearance: ms_per_frame=.. frames_per_s=.. extract_ms=.. match_ms=..
// mcl_ms=.. training_frames=N particles=P speedup_vs_paper_single=.. speedup_vs_paper_mcl=..`.
#include <chrono>
#include <cstdio>

#include "adaptive_perception/localization/appearance_mcl.h"
#include "adaptive_perception/places/room_classifier.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/sim/indoor_renderer.h"
#include "adaptive_perception/sim/indoor_route.h"
#include "command_line.h"

using namespace adaptive_perception;
using Clock = std::chrono::steady_clock;

namespace {
double msSince(Clock::time_point t0) {
  return 1e3 * std::chrono::duration<double>(Clock::now() - t0).count();
}
// Images (and their true poses and places) of one run, `count` of them evenly over the route.
void renderRun(const sim::IndoorWorld& world, const sim::IndoorRenderer& renderer, int count,
               std::uint64_t seed, std::vector<cv::Mat>* images, std::vector<math::SE2>* poses,
               std::vector<std::string>* places) {
  math::Rng rng(seed);
  const sim::IndoorLighting light =
      sim::IndoorLighting::sample(sim::IndoorLightingKind::kCloudy, rng);
  sim::IndoorRoute robot(world, rng.split());
  const double dt = sim::IndoorRoute::duration(world) / count;
  for (int i = 0; i < count; ++i) {
    robot.step(dt);
    const math::SE2 p = robot.truePose();
    const int place = world.placeAt({p.x_m, p.y_m});
    if (place < 0) continue;
    images->push_back(renderer.render(p, light, rng));
    poses->push_back(p);
    places->push_back(world.places[place].name);
  }
}
}  // namespace

int main(int argc, char** argv) {
  tools::CommandLine cli("bench_appearance",
                         "Speed of SIFT room classification and appearance MCL on one core, on a "
                         "training set rendered from the indoor simulator.");
  long frames = 1700;
  cli.option("frames", &frames, config::closed(10, 100000), "training frames");
  long particles = 100;
  cli.option("particles", &particles, config::closed(1, 100000), "MCL particles");
  long test_frames = 100;
  cli.option("test_frames", &test_frames, config::closed(1, 10000), "test frames");
  const std::uint64_t& seed = cli.seed();
  places::RoomClassifierConfig cfg;
  cfg.structure.weight = 0.0;  // SIFT alone unless asked: the paper's classifier
  cli.fields(places::RoomClassifierConfig::fields(), &cfg, {"structure_weight"});
  cli.parse(argc, argv);
  cv::setNumThreads(1);  // one core, as the target says (OpenCV would parallelise SIFT)
  try {
    const sim::IndoorWorld world = sim::IndoorWorld::loadYaml(
        ros_params::resolvePackagePath("config/worlds/indoor_building.yaml"));
    const sim::IndoorRenderer renderer(world, {});
    std::vector<cv::Mat> train_img, test_img;
    std::vector<math::SE2> train_pose, test_pose;
    std::vector<std::string> train_place, test_place;
    renderRun(world, renderer, static_cast<int>(frames), seed, &train_img, &train_pose,
              &train_place);
    renderRun(world, renderer, static_cast<int>(test_frames), seed + 1, &test_img, &test_pose,
              &test_place);
    cfg.validate();
    std::vector<places::TrainingFrame> tf;
    for (size_t i = 0; i < train_img.size(); ++i) {
      places::TrainingFrame f;
      f.image_id = static_cast<long>(i);
      f.place = train_place[i];
      f.features = places::extractSift(train_img[i], cfg.sift);
      if (cfg.structure.enabled()) f.structure = places::lineStructure(train_img[i], cfg.lines);
      f.has_pose = true;
      f.x_m = train_pose[i].x_m;
      f.y_m = train_pose[i].y_m;
      f.yaw_rad = train_pose[i].yaw_rad;
      tf.push_back(f);
    }
    places::RoomClassifier classifier(cfg);
    const auto t_build = Clock::now();
    classifier.setFrames(tf);
    const double build_ms = msSince(t_build);
    std::vector<localization::PosedFrame> posed;
    for (const auto& f : classifier.frames())
      posed.push_back({math::SE2(f.x_m, f.y_m, f.yaw_rad), classifier.roomIndex(f.place)});
    localization::AppearanceMclConfig mc;
    mc.particles = static_cast<int>(particles);
    localization::AppearanceMcl mcl(posed, static_cast<int>(classifier.rooms().size()), mc, seed);

    double extract = 0.0, match = 0.0, step = 0.0;
    for (size_t i = 0; i < test_img.size(); ++i) {
      auto t0 = Clock::now();
      const places::ImageCues cues = classifier.extract(test_img[i]);
      extract += msSince(t0);
      t0 = Clock::now();
      const auto sims = classifier.frameSimilarities(cues, cfg.index.candidates);
      match += msSince(t0);
      t0 = Clock::now();
      mcl.step(std::nullopt, sims);
      step += msSince(t0);
    }
    const double n = static_cast<double>(test_img.size());
    const double per = (extract + match + step) / n;
    std::printf(
        "bench_appearance: ms_per_frame=%.1f frames_per_s=%.1f extract_ms=%.1f match_ms=%.1f "
        "mcl_ms=%.2f index_build_ms=%.0f training_frames=%zu particles=%ld "
        "speedup_vs_paper_single=%.0f speedup_vs_paper_mcl=%.0f\n",
        per, 1e3 / per, extract / n, match / n, step / n, build_ms, classifier.frames().size(),
        particles, 180e3 / ((extract + match) / n), 3500.0 / per);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_appearance: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
