// train_places: builds (or extends) a place database from labelled images.
//
//   train_places --help   (every option with its default, unit and range)
//
// Images come from a bag (camera/image_raw labelled by ground_truth/place) or a CSV list of
// `image_path,place` lines. Per place, --images_per_place images spread evenly over that place's
// images are stored (0: all), with their histograms in every colour space of the database and
// their whole-image descriptors (places/global_descriptor.h, default settings). A new
// database takes --bins/--spaces/--mask (defaults 256, all eight spaces, no mask); an existing one
// keeps its own, and explicit options that differ are refused. Adjacency: consecutive images with
// different places make the two places adjacent (the route walked), unless --no_adjacency.
// --route: a reference drive for the route filter: every image its own place (route_NNNNNN in the
// order read), each joined to the one before.
// --features also stores each image's SIFT descriptors, its line-structure descriptor (default
// LineStructureConfig) and, from bags, its ground_truth/pose (the training frames of the room
// classifier and the appearance localizer, papers/002).
// The whole run is one transaction, and holds the database's write lock from the start: a run
// killed at any point leaves the database as it was, and a second writer is refused at once. A
// place already in the database gets its images replaced (a rerun does not duplicate them); its
// edges stay and new ones are added. Last line:
// `train_places: database=DB places=N images_added=M images_total=T edges=E seconds=S`.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <set>

#include "adaptive_perception/places/feature_index.h"
#include "adaptive_perception/places/line_structure.h"
#include "adaptive_perception/places/place_database.h"
#include "labelled_images.h"
#include "progress.h"
#include "command_line.h"

using namespace adaptive_perception;

int main(int argc, char** argv) {
  tools::CommandLine cli("train_places",
                         "Builds (or extends) a place database from labelled images, in one "
                         "transaction.");
  std::string bag;
  cli.option("bag", &bag, "bag of labelled images (camera/image_raw, ground_truth/place)");
  std::string list;
  cli.option("list", &list, "CSV list of image_path,place lines");
  std::string db_path;
  cli.option("database", &db_path, "the database (created, or extended)")->required();
  long per_place = 15;
  cli.option("images_per_place", &per_place, config::closed(0, 1e9),
             "images stored per place, spread evenly (0: all)");
  // A new database takes these; an existing one keeps its own and refuses explicit ones that
  // differ.
  long bins = 256;
  tools::CommandLine::Option* bins_opt =
      cli.option("bins", &bins, "histogram bins per channel (a new database)");
  std::string spaces = "all";
  tools::CommandLine::Option* spaces_opt = cli.option(
      "spaces", &spaces, "colour spaces (a new database): all or a comma-separated list");
  std::string mask = "none";
  tools::CommandLine::Option* mask_opt =
      cli.option("mask", &mask, "image mask (a new database): none, auto or ring:cx,cy,r_in,r_out");
  bool no_adjacency = false;
  cli.flag("no_adjacency", &no_adjacency,
           "consecutive images of different places do not make the places adjacent");
  bool route = false;
  cli.flag("route", &route,
           "a reference drive: every image is a place of its own (route_000000, ... in the order "
           "read) joined to the one before, the database the route filter follows "
           "(histogram_place_recognizer ~use_route); --images_per_place is not used");
  bool features = false;
  cli.flag("features", &features,
           "also stores SIFT, line-structure descriptors and poses (room classifier, appearance "
           "localizer)");
  places::SiftConfig sift;
  cli.option("max_features", &sift.max_features, "SIFT features kept per image");
  cli.parse(argc, argv);
  const bool explicit_settings = bins_opt->count() + spaces_opt->count() + mask_opt->count() > 0;
  const bool adjacency = !no_adjacency;
  if (route && no_adjacency)
    cli.fail("--route joins each image to the one before: not with --no_adjacency");
  if (bag.empty() == list.empty()) cli.fail("give exactly one of --bag FILE and --list CSV");
  try {
    sift.validate();
  } catch (const std::invalid_argument& e) {
    cli.fail(std::string("--max_features: ") + e.what());
  }
  const auto t_start = std::chrono::steady_clock::now();
  try {
    places::HistogramConfig hc;
    hc.bins = static_cast<int>(bins);
    hc.spaces = places::parseSpaces(spaces);
    hc.mask = places::MaskConfig::parse(mask);
    hc.validate();
    const places::DatabaseSettings wanted = places::DatabaseSettings::fromHistogramConfig(hc);
    places::PlaceDatabase db = places::PlaceDatabase::openOrCreate(db_path, wanted);
    if (explicit_settings) db.requireSettings(wanted);
    if (route && !db.places().empty())
      throw std::runtime_error(db_path + ": --route makes a database of one drive; this one has " +
                               std::to_string(db.places().size()) +
                               " places already (give a new file)");
    db.beginBatch();
    const places::HistogramConfig use = db.settings().histogramConfig();
    const places::GlobalDescriptorConfig descriptors =
        places::descriptorConfigForMask(use.mask);
    db.useDescriptors(descriptors);

    // Histograms of every image, grouped by place in arrival order.
    std::map<std::string, std::vector<places::TrainingImage>> by_place;
    std::set<std::pair<std::string, std::string>> edges;
    std::string previous;
    tools::Progress progress("train_places", 0, "images");
    long seen = 0;
    const long n = tools::forEachLabelledImage(bag, list, [&](const tools::LabelledImage& li) {
      progress.update(++seen);
      places::TrainingImage ti;
      ti.source = li.source;
      ti.stamp_s = li.stamp_s;
      ti.histograms = places::computeHistograms(li.bgr, use);
      ti.descriptors = places::computeDescriptors(li.bgr, descriptors);
      if (features) {
        ti.features = places::extractSift(li.bgr, sift);
        ti.structure = places::lineStructure(li.bgr, places::LineStructureConfig{});
        ti.pose = li.pose;
      }
      std::string label = li.label;
      if (route) {
        char name[32];
        std::snprintf(name, sizeof name, "route_%06ld", seen - 1);
        label = name;
      }
      by_place[label].push_back(std::move(ti));
      if (!previous.empty() && previous != label) edges.insert(std::minmax(previous, label));
      previous = label;
    }, route);
    progress.finish();
    if (n == 0) throw std::runtime_error("no labelled image in " + (bag.empty() ? list : bag));
    long added = 0;
    for (auto& [place, images] : by_place) {
      std::vector<places::TrainingImage> chosen;
      const size_t total = images.size();
      const size_t k = per_place == 0 ? total : std::min<size_t>(total, per_place);
      for (size_t i = 0; i < k; ++i)
        chosen.push_back(std::move(images[(2 * i + 1) * total / (2 * k)]));
      int replaced = 0;
      added += db.replaceImages(place, chosen, &replaced);
      std::cerr << "train_places: " << place << ": " << chosen.size() << " of " << total
                << " images";
      if (replaced > 0) std::cerr << " (replacing the " << replaced << " it had)";
      std::cerr << "\n";
    }
    if (adjacency)
      for (const auto& [a, b] : edges) db.setAdjacent(a, b);
    db.commitBatch();
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    std::printf(
        "train_places: database=%s places=%zu images_added=%ld images_total=%ld edges=%zu "
        "seconds=%.1f\n",
        db_path.c_str(), db.places().size(), added, db.imageCount(), db.edges().size(), secs);
  } catch (const std::exception& e) {
    std::cerr << "train_places: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
