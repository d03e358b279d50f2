// bench_ekf_slam: the cost of one line-landmark EKF SLAM scan (prediction, JCBB association, the
// stacked Joseph update of 8 observed lines) against the number of landmarks in the state, with
// Google Benchmark's complexity fit (the update is O(n^2) in the state size).
//
//   bench_ekf_slam [--benchmark_filter=...] [--benchmark_format=console|csv|json]
//
// The map: n distinct lines around the robot (no two compatible), built once per size; each
// iteration predicts a small motion and updates with 8 of them (noise-free observations of the
// current estimate, so association always succeeds and the state stays the same size).
// BM_MapSnapshot and BM_MapSave: what ~save_map costs (the copy under the node's lock, the write).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "adaptive_perception/slam/line_ekf_slam.h"
#include "adaptive_perception/slam/map_io.h"

using namespace adaptive_perception;

namespace {
slam::LineObservation observation(const slam::Line& l) {
  slam::LineObservation o;
  o.line = l;
  o.cov = Eigen::Vector2d(1e-4, 1e-5).asDiagonal();
  const Eigen::Vector2d n(std::cos(l.alpha_rad), std::sin(l.alpha_rad)), t(-n.y(), n.x());
  o.start_m = l.rho_m * n - t;
  o.end_m = l.rho_m * n + t;
  return o;
}

slam::LineEkfSlam makeMap(int n) {
  slam::LineEkfSlamConfig cfg;
  cfg.confirm_sightings = 1;
  cfg.merge_landmarks = false;
  slam::LineEkfSlam ekf(cfg, math::SE2(), Eigen::Vector3d(1e-4, 1e-4, 1e-5).asDiagonal());
  std::vector<slam::LineObservation> obs;
  for (int k = 0; k < n; ++k) {
    const double alpha = std::fmod(2.399963 * k, 2.0 * M_PI) - M_PI;  // golden-angle spread
    obs.push_back(observation(slam::Line{2.0 + 0.7 * (k % 20), alpha}));
  }
  ekf.update(obs);
  return ekf;
}

void BM_ScanUpdate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  slam::LineEkfSlam ekf = makeMap(n);
  for (auto _ : state) {
    ekf.predict(math::SE2(0.01, 0.0, 0.001));
    std::vector<slam::LineObservation> obs;
    for (int k = 0; k < 8; ++k) {
      const int i = (k * n) / 8;
      Eigen::Matrix<double, 2, 3> hr;
      Eigen::Matrix2d hl;
      obs.push_back(observation(slam::observeLine(ekf.pose(), ekf.landmark(i), &hr, &hl)));
    }
    const auto res = ekf.update(obs);
    benchmark::DoNotOptimize(res.matched);
  }
  state.counters["landmarks"] = ekf.numLandmarks();
  state.SetComplexityN(2 * n + 3);
}
BENCHMARK(BM_ScanUpdate)
    ->Arg(10)
    ->Arg(25)
    ->Arg(50)
    ->Arg(100)
    ->Arg(200)
    ->Arg(400)
    ->Unit(benchmark::kMicrosecond)
    ->Complexity(benchmark::oNSquared);

// ekf_slam_mapper's ~save_map: the copy taken under the node's lock (all the node waits for), and
// the file written from it on the service thread (bytes: the file's size).
void BM_MapSnapshot(benchmark::State& state) {
  const slam::LineEkfSlam ekf = makeMap(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const slam::LineEkfSlam copy(ekf);
    benchmark::DoNotOptimize(copy.covariance().data());
  }
  state.counters["landmarks"] = ekf.numLandmarks();
}
BENCHMARK(BM_MapSnapshot)->Arg(120)->Arg(480)->Unit(benchmark::kMillisecond);

void BM_MapSave(benchmark::State& state) {
  const slam::LineEkfSlam ekf = makeMap(static_cast<int>(state.range(0)));
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("bench_ekf_slam_map_" + std::to_string(::getpid()) + ".yaml"))
                               .string();
  for (auto _ : state) slam::writeLineMapYaml(path, ekf);
  state.counters["landmarks"] = ekf.numLandmarks();
  state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
  std::filesystem::remove(path);
}
BENCHMARK(BM_MapSave)->Arg(120)->Arg(480)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
