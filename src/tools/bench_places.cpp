// bench_places: place-recognition speed on one core.
//
//   bench_places --help   (every option with its default, unit and range)
//
// 1. Histogram extraction of a 640 x 480 rendering of the indoor building (the kitchen, cloudy),
//    each colour space alone and all eight together (ms per image).
// 2. Queries: eq. (5) node distances of one test image against --images stored images (11
//    places; histograms of rendered views of the building, perturbed per stored image) in one
//    colour space, for each distance (ms per query; the target is under 10 ms for 10,000 images).
// 3. Traversals (places/traversal_matcher.h): each whole-image descriptor of the 640 x 480 image
//    and its SIFT descriptors (ms), and one query against a reference traversal of --images images
//    (rendered views along the building's route; the bag of words with its default 500-word
//    vocabulary) with each method, the sequence search included (ms per query, after
//    sequence_frames queries so the search runs over its whole history; the words' time is the
//    word assignment and the cosines, the SIFT extraction is describe_ms_sift).
// Last line: `bench_places: extract_ms_<space>=... extract_ms_all=... query_ms_<method>=...
// describe_ms_<descriptor>=... traversal_ms_<method>=... images=N space=S`.
#include <cmath>
#include <cstdio>
#include <string>

#include "adaptive_perception/places/feature_index.h"
#include "adaptive_perception/places/histogram.h"
#include "adaptive_perception/places/place_matcher.h"
#include "adaptive_perception/places/traversal_matcher.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/sim/indoor_renderer.h"
#include "bench_timing.h"
#include "command_line.h"

using namespace adaptive_perception;

namespace {
template <typename F>
double msPerCall(double seconds, F&& f) {
  return 1e3 / tools::unitsPerSecond(seconds, [&] {
    f();
    return 1;
  });
}
}  // namespace

int main(int argc, char** argv) {
  tools::CommandLine cli("bench_places",
                         "Place-recognition speed on one core: histogram extraction, queries "
                         "against stored images, and traversal descriptors.");
  long images = 10000;
  cli.option("images", &images, config::closed(1, 1000000), "stored images");
  std::string space_name = "hsv";
  std::vector<std::string> spaces;
  for (int i = 0; i < places::kNumSpaces; ++i) spaces.push_back(places::spaceName(i));
  cli.option("space", &space_name, "colour space of the queries")->oneOf(spaces);
  long bins = 256;
  cli.option("bins", &bins, config::closed(2, 256), "histogram bins");
  const double& seconds = cli.measurementSeconds(1.0);
  const std::uint64_t& seed = cli.seed();
  cli.parse(argc, argv);
  try {
    const int space = places::spaceIndex(space_name);
    const sim::IndoorWorld world = sim::IndoorWorld::loadYaml(
        ros_params::resolvePackagePath("config/worlds/indoor_building.yaml"));
    sim::IndoorCameraConfig cam;
    cam.width_px = 640;
    cam.height_px = 480;
    const sim::IndoorRenderer renderer(world, cam);
    math::Rng rng(seed);
    const sim::IndoorLighting light =
        sim::IndoorLighting::sample(sim::IndoorLightingKind::kCloudy, rng);
    const cv::Mat kitchen = renderer.render(math::SE2(3.5, 11.8, 1.0), light, rng);

    std::string line = "bench_places:";
    char buf[96];
    for (int s = 0; s < places::kNumSpaces; ++s) {
      const double ms = msPerCall(seconds / 4, [&] {
        places::computeHistograms(kitchen, cv::Mat(), static_cast<int>(bins), {s});
      });
      std::snprintf(buf, sizeof(buf), " extract_ms_%s=%.2f", places::spaceName(s).c_str(), ms);
      line += buf;
    }
    const std::vector<int> all = places::parseSpaces("all");
    const double ms_all = msPerCall(seconds / 2, [&] {
      places::computeHistograms(kitchen, cv::Mat(), static_cast<int>(bins), all);
    });
    std::snprintf(buf, sizeof(buf), " extract_ms_all=%.2f", ms_all);
    line += buf;

    // A database of `images` stored histograms: 40 rendered views (small images are enough for
    // histograms), each stored many times with multiplicative noise on every bin, renormalised.
    sim::IndoorCameraConfig small;
    small.width_px = 160;
    small.height_px = 120;
    const sim::IndoorRenderer small_renderer(world, small);
    std::vector<places::ImageHistograms> views;
    std::vector<int> view_place;
    for (int v = 0; v < 40; ++v) {
      const auto& stop = world.route[rng.uniformInt(0, static_cast<int>(world.route.size()) - 1)];
      const math::SE2 pose(stop.xy_m.x(), stop.xy_m.y(), rng.uniform(-M_PI, M_PI));
      views.push_back(places::computeHistograms(small_renderer.render(pose, light, rng), cv::Mat(),
                                                static_cast<int>(bins), {space}));
      view_place.push_back(std::max(0, world.placeAt(stop.xy_m)));
    }
    places::PlaceIndex index(static_cast<int>(bins));
    for (const auto& p : world.places) index.addPlace(p.name);
    for (long i = 0; i < images; ++i) {
      const int v = static_cast<int>(i % views.size());
      places::ImageHistograms h = views[v];
      std::vector<float>& x = h.spaces[space];
      for (int band = 0; band < 3; ++band) {
        double sum = 0.0;
        for (long b = 0; b < bins; ++b)
          sum += (x[band * bins + b] *= static_cast<float>(rng.uniform(0.8, 1.2)));
        for (long b = 0; b < bins; ++b)
          x[band * bins + b] = static_cast<float>(x[band * bins + b] / sum);
      }
      index.addImage(view_place[v], h);
    }
    const places::ImageHistograms query =
        places::computeHistograms(kitchen, cv::Mat(), static_cast<int>(bins), {space});
    double sink = 0.0;
    for (int m = 0; m < places::kNumDistances; ++m) {
      const auto d = static_cast<places::Distance>(m);
      const double ms =
          msPerCall(seconds, [&] { sink += index.nodeDistances(space, d, query)[0]; });
      std::snprintf(buf, sizeof(buf), " query_ms_%s=%.2f", places::distanceName(d).c_str(), ms);
      line += buf;
    }

    // 3. Traversals.
    const places::TraversalMatcherConfig tcfg;
    for (int k = 0; k < places::kNumDescriptorKinds; ++k) {
      const auto kind = static_cast<places::DescriptorKind>(k);
      const double ms = msPerCall(seconds / 4, [&] {
        sink += places::computeDescriptor(kitchen, kind, tcfg.descriptor).at<uchar>(0, 0);
      });
      std::snprintf(buf, sizeof(buf), " describe_ms_%s=%.2f", places::descriptorName(kind).c_str(),
                    ms);
      line += buf;
    }
    {
      const double ms = msPerCall(seconds / 4, [&] {
        sink += places::extractSift(kitchen, places::SiftConfig()).rows;
      });
      std::snprintf(buf, sizeof(buf), " describe_ms_sift=%.2f", ms);
      line += buf;
    }
    std::vector<places::ImageDescriptors> route_views;
    for (int v = 0; v < 40; ++v) {
      const auto& stop = world.route[v * world.route.size() / 40];
      const cv::Mat view =
          small_renderer.render(math::SE2(stop.xy_m.x(), stop.xy_m.y(), 0.0), light, rng);
      route_views.push_back(places::computeDescriptors(view, tcfg.descriptor));
      route_views.back().sift = places::extractSift(view, places::SiftConfig());
    }
    places::ReferenceTraversal refs(tcfg.descriptor);
    std::vector<cv::Mat> ref_sift;
    for (long i = 0; i < images; ++i) {
      refs.add(route_views[i % route_views.size()]);
      ref_sift.push_back(route_views[i % route_views.size()].sift);
    }
    refs.learnWords(ref_sift);  // the default vocabulary (500 words)
    places::ImageDescriptors tquery = places::computeDescriptors(kitchen, tcfg.descriptor);
    tquery.sift = places::extractSift(kitchen, places::SiftConfig());
    for (const char* method :
         {"thumbnail", "gradient", "chromaticity", "layout", "words", "fused", "sequence", "route"}) {
      places::TraversalMatcherConfig c = tcfg;
      c.method = method;
      places::TraversalMatcher matcher(refs, c);
      for (int i = 0; i < c.sequence.sequence_frames; ++i) matcher.add(tquery);
      const double ms = msPerCall(seconds, [&] { sink += matcher.add(tquery)[0]; });
      std::snprintf(buf, sizeof(buf), " traversal_ms_%s=%.2f", method, ms);
      line += buf;
    }
    if (std::isnan(sink)) line += " (nan)";
    std::snprintf(buf, sizeof(buf), " images=%ld space=%s bins=%ld", images, space_name.c_str(),
                  bins);
    std::printf("%s%s\n", line.c_str(), buf);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_places: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
