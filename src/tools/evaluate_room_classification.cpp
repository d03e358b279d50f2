// evaluate_room_classification: SIFT image-to-room classification (papers/002 section 4.1.1) of
// labelled test images against the training frames of a place database, scored as ImageCLEF 2009
// RobotVision does (+1 correct, -0.5 wrong, 0 not classified).
//
//   evaluate_room_classification --help   (every option with its default, unit and range)
//
// The database needs training frames with features (train_places --features; poses too for mcl).
// Mode `single` classifies every image alone (the paper's obligatory track, Table 3). Mode `mcl`
// runs the appearance Monte Carlo localizer (localization/appearance_mcl.h, the optional track,
// Table 5) from a global start: particle weights from the similarities of the indexed matcher's
// verified frames, motion from the bag's odom (or the training run's average step for image
// lists); a frame is classified only while the filter is stable.
// --structure_weight W > 0 joins the line-structure similarity (places/line_structure.h, section
// 4.1.2) to the SIFT similarity in both modes; the database must hold the descriptors (train_places
// --features stores them).
// Writes DIR/results.yaml (counts, confusion) and DIR/images.csv (image, truth, predicted, share,
// features, ms). Last line: `evaluate_room_classification: mode=single score=.. correct=..
// misclassified=.. not_classified=.. frames=.. score_per_frame=.. frames_per_s=..`.
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "adaptive_perception/localization/appearance_mcl.h"
#include "adaptive_perception/places/room_classifier.h"
#include "command_line.h"
#include "labelled_images.h"

using namespace adaptive_perception;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  tools::CommandLine cli("evaluate_room_classification",
                         "SIFT image-to-room classification (papers/002 section 4.1.1) of "
                         "labelled test images against the training frames of a place database, "
                         "scored as ImageCLEF 2009 RobotVision does.");
  std::string db_path;
  cli.option("database", &db_path, "place database with training frames and features")->required();
  std::string bag;
  cli.option("bag", &bag, "bag of labelled test images");
  std::string list;
  cli.option("list", &list, "CSV list of labelled test images");
  std::string mode = "single";
  cli.option("mode", &mode, "every image alone (single) or the appearance Monte Carlo localizer")
      ->oneOf({"single", "mcl"});
  // The room classifier's and the localizer's parameters (the same names and ranges as
  // appearance_localizer's and histogram_place_recognizer's).
  places::RoomClassifierConfig cfg;
  cli.fields(places::RoomClassifierConfig::fields(), &cfg);
  localization::AppearanceMclConfig mcl_cfg;
  cli.fields(localization::AppearanceMclConfig::fields(), &mcl_cfg);
  long max_images = 0;
  cli.option("max_images", &max_images, config::closed(0, 1e9), "test images (0: all)");
  const std::uint64_t& seed = cli.seed();
  const std::string& output = cli.resultsFolder("the results");
  cli.parse(argc, argv);
  if (bag.empty() == list.empty()) cli.fail("give exactly one of --bag FILE and --list CSV");
  try {
    cfg.validate();
    const places::PlaceDatabase db = places::PlaceDatabase::open(db_path, true);
    if (db.recoveredJournal())
      std::cerr << "evaluate_room_classification: " << db_path
                << ": an interrupted write (a killed train_places?) was rolled back\n";
    places::RoomClassifier classifier(cfg);
    const auto t_load = Clock::now();
    classifier.setFrames(db.loadFrames());
    const double load_s = std::chrono::duration<double>(Clock::now() - t_load).count();
    const auto& rooms = classifier.rooms();
    std::cerr << "evaluate_room_classification: " << classifier.frames().size()
              << " training frames in " << rooms.size() << " rooms, index built in " << load_s
              << " s\n";

    std::unique_ptr<localization::AppearanceMcl> mcl;
    if (mode == "mcl") {
      std::vector<localization::PosedFrame> posed;
      for (const auto& f : classifier.frames()) {
        if (!f.has_pose)
          throw std::runtime_error(db_path + ": training frame " + std::to_string(f.image_id) +
                                   " has no pose (train from a bag with ground_truth/pose)");
        posed.push_back({math::SE2(f.x_m, f.y_m, f.yaw_rad), classifier.roomIndex(f.place)});
      }
      mcl = std::make_unique<localization::AppearanceMcl>(posed, static_cast<int>(rooms.size()),
                                                          mcl_cfg, seed);
    }
    std::optional<math::SE2> last_odom;
    long reinits = 0, unknown = 0;
    fs::create_directories(output);
    std::ofstream csv(fs::path(output) / "images.csv");
    csv << "image,truth,predicted,share,features,ms\n";
    places::ClefScore score;
    std::vector<std::vector<long>> confusion(rooms.size() + 1,
                                             std::vector<long>(rooms.size() + 1, 0));
    double busy_s = 0.0;
    long n = 0;
    tools::forEachLabelledImage(bag, list, [&](const tools::LabelledImage& li) {
      if (max_images > 0 && n >= max_images) return;
      const auto t0 = Clock::now();
      const places::ImageCues cues = classifier.extract(li.bgr);
      places::RoomClassification r;
      if (!mcl) {
        r = classifier.classifyCues(cues);
      } else {
        // Particle weights from every verified candidate frame, not only the best n.
        const auto sims = classifier.frameSimilarities(cues, cfg.index.candidates);
        r.features = cues.sift.rows;
        std::optional<math::SE2> delta;
        if (li.odom) {
          const math::SE2 o((*li.odom)[0], (*li.odom)[1], (*li.odom)[2]);
          if (last_odom) delta = math::between(*last_odom, o);
          last_odom = o;
        }
        const localization::AppearanceEstimate e = mcl->step(delta, sims);
        r.room = e.room;
        r.share = e.room >= 0 ? e.room_weights[e.room] : 0.0;
        reinits += e.reinitialized;
        unknown += e.unknown_room;
      }
      const double s = std::chrono::duration<double>(Clock::now() - t0).count();
      busy_s += s;
      const int truth = classifier.roomIndex(li.label);
      // A test room the training never saw can only be "not classified" (0) or wrong.
      score.add(r.room, truth < 0 ? -2 : truth);
      confusion[truth < 0 ? rooms.size() : truth][r.room < 0 ? rooms.size() : r.room] += 1;
      csv << n << "," << li.label << "," << (r.room < 0 ? "not_classified" : rooms[r.room]) << ","
          << r.share << "," << r.features << "," << 1e3 * s << "\n";
      ++n;
    });
    if (n == 0) throw std::runtime_error("no labelled test image");
    const double fps = n / std::max(busy_s, 1e-9);
    YAML::Emitter y;
    y << YAML::BeginMap;
    y << YAML::Key << "database" << YAML::Value << db_path;
    y << YAML::Key << "mode" << YAML::Value << mode;
    y << YAML::Key << "training_frames" << YAML::Value << classifier.frames().size();
    y << YAML::Key << "best_frames" << YAML::Value << cfg.best_frames;
    y << YAML::Key << "min_share" << YAML::Value << cfg.min_share;
    y << YAML::Key << "structure_weight" << YAML::Value << cfg.structure.weight;
    y << YAML::Key << "structure_floor" << YAML::Value << cfg.structure.floor;
    y << YAML::Key << "score" << YAML::Value << score.score();
    y << YAML::Key << "correct" << YAML::Value << score.correct;
    y << YAML::Key << "misclassified" << YAML::Value << score.misclassified;
    y << YAML::Key << "not_classified" << YAML::Value << score.not_classified;
    y << YAML::Key << "frames" << YAML::Value << n;
    y << YAML::Key << "frames_per_s" << YAML::Value << fps;
    if (mcl) {
      y << YAML::Key << "particles" << YAML::Value << mcl_cfg.particles;
      y << YAML::Key << "reinitializations" << YAML::Value << reinits;
      y << YAML::Key << "unknown_room_frames" << YAML::Value << unknown;
    }
    y << YAML::Key << "confusion" << YAML::Value << YAML::BeginMap;
    for (size_t t = 0; t <= rooms.size(); ++t) {
      y << YAML::Key << (t < rooms.size() ? rooms[t] : "unknown_room") << YAML::Value << YAML::Flow
        << YAML::BeginMap;
      for (size_t p = 0; p <= rooms.size(); ++p)
        if (confusion[t][p] > 0)
          y << YAML::Key << (p < rooms.size() ? rooms[p] : "not_classified") << YAML::Value
            << confusion[t][p];
      y << YAML::EndMap;
    }
    y << YAML::EndMap << YAML::EndMap;
    std::ofstream(fs::path(output) / "results.yaml") << y.c_str() << "\n";
    std::printf(
        "evaluate_room_classification: mode=%s score=%.1f correct=%ld misclassified=%ld "
        "not_classified=%ld frames=%ld score_per_frame=%.3f frames_per_s=%.1f\n",
        mode.c_str(), score.score(), score.correct, score.misclassified, score.not_classified, n,
        score.score() / n, fps);
  } catch (const std::exception& e) {
    std::cerr << "evaluate_room_classification: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
