// evaluate_places: recognises the places of labelled test images against a place database, the
// paper's way (papers/004 sections 5-7) and with the topological Bayes filter. With --reference
// and --query it runs the standard protocol on two traversals instead (place_traversal.h).
//
//   evaluate_places --help   (every option with its default, unit and range)
//
// 1. The paper's protocol: for each test place, --images_per_place of its images (spread evenly)
//    form one test set; every colour space and method gives a place and a confidence (eqs. 5-7),
//    printed as the paper's Tables 1-7, and so does each whole-image cue (thumbnail, gradient,
//    chromaticity, fused; the nearest training image of each place, place_descriptor_index.h).
//    The answer is --cue's (default fused; "histogram": the paper's most confident space and
//    method, section 6). `accuracy` is the fraction of test places answered right,
//    `mean_confidence` the mean of the answers' confidences; `paper_accuracy` is the paper's
//    most-confident rule over the colour histograms.
// 2. Single images: every test image alone, per space and method and per cue; `best_space
//    best_method` have the highest single-image accuracy of the histograms
//    (`histogram_single_image_accuracy`), `single_image_accuracy` is --cue's.
// 3. Sequences, with --cue (histogram: the best space and method): a sliding window of --window
//    successive images (eqs. 6-7, `window_accuracy`) and the Bayes filter over the database's
//    adjacency (`filter_accuracy`; with a whole-image cue it also takes the sequence matcher's
//    view of the last images over the training images in stored order with --use_sequence 1),
//    scored against each window's last image.
// A database stored without whole-image descriptors (before they existed) is evaluated with the
// histograms alone, with a warning.
// `queries_per_s`: single-image queries (eq. 5 over the whole database) per second, best space
// and method, one core. Writes DIR/results.yaml (all tables) and DIR/images.csv (per image: truth,
// single-image answer, window answer, filter answer). Last line:
// `evaluate_places: accuracy=.. mean_confidence=.. cue=.. paper_accuracy=.. best_space=..
//  best_method=.. histogram_single_image_accuracy=.. single_image_accuracy=.. window_accuracy=..
//  filter_accuracy=.. queries_per_s=.. places=.. test_images=..`
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "adaptive_perception/places/place_database.h"
#include "adaptive_perception/places/place_recognizer.h"
#include "command_line.h"
#include "labelled_images.h"
#include "place_traversal.h"
#include "progress.h"

using namespace adaptive_perception;
using places::Distance;
namespace fs = std::filesystem;

namespace {
std::string pct(double c) {
  char b[16];
  std::snprintf(b, sizeof(b), "%.1f", 100.0 * c);
  return b;
}
}  // namespace

int main(int argc, char** argv) {
  tools::CommandLine cli("evaluate_places",
                         "Recognises the places of labelled test images against a place database "
                         "(papers/004 sections 5-7, and the topological Bayes filter); with "
                         "--reference and --query, the standard protocol on two traversals.");
  std::string db_path;
  cli.option("database", &db_path,
             "place database (labelled images; in traversal mode: the stored references)");
  const std::string& output = cli.resultsFolder("the results");
  const std::string group = "Labelled test images (--database with --bag or --list)";
  std::string bag;
  cli.option("bag", &bag, "bag of labelled test images")->group(group);
  std::string list;
  cli.option("list", &list, "CSV list of labelled test images")->group(group);
  long per_place = 15;
  cli.option("images_per_place", &per_place, config::closed(1, 1e9),
             "test images per place (spread evenly)")
      ->group(group);
  std::string spaces_arg;
  cli.option("spaces", &spaces_arg, "colour spaces of the tables: all or a comma-separated list")
      ->group(group);
  std::string methods_arg = "paper";
  cli.option("methods", &methods_arg,
             "distances of the tables: paper, all or a comma-separated list of chi_square, "
             "jeffrey, ks, ks_cumulative, intersection")
      ->group(group);
  places::PlaceRecognizerConfig rc;
  cli.option("cue", &rc.cue,
             "the answer's cue: fused, thumbnail, gradient, chromaticity, layout or histogram")
      ->group(group);
  // histogram_place_recognizer's parameters of the same names and ranges; the fusion weights
  // apply in both protocols.
  cli.fields(places::PlaceRecognizerConfig::fields(), &rc,
             {"window", "stay_probability", "likelihood_sharpness", "use_sequence",
              "thumbnail_weight", "gradient_weight", "chromaticity_weight", "layout_weight"});
  cli.option("words_weight", &rc.fusion.words, config::closed(0, 1e6),
             "weight of the bag of SIFT words in the fused cue (traversals only)");
  tools::TraversalOptions traversal;
  tools::addTraversalOptions(cli, &traversal);
  cli.parse(argc, argv);
  if (!traversal.reference.empty() || !traversal.query.empty())
    return tools::runTraversalEvaluation(cli, traversal, rc.fusion, db_path, output);
  if (db_path.empty()) cli.fail("--database DB.sqlite is required");
  if (bag.empty() == list.empty()) cli.fail("give exactly one of --bag FILE and --list CSV");
  try {
    rc.validate();
    const places::PlaceDatabase db = places::PlaceDatabase::open(db_path, true);
    if (db.recoveredJournal())
      std::cerr << "evaluate_places: " << db_path
                << ": an interrupted write (a killed train_places?) was rolled back\n";
    const std::vector<int> spaces =
        spaces_arg.empty() ? db.settings().spaces : places::parseSpaces(spaces_arg);
    const std::vector<Distance> methods = places::parseDistances(methods_arg);
    const places::PlaceIndex index = db.loadIndex(spaces);
    if (index.numPlaces() == 0) throw std::runtime_error(db_path + ": the database has no place");
    const places::HistogramConfig hc = db.settings().histogramConfig();
    const places::GlobalDescriptorConfig dc = places::descriptorConfigForMask(hc.mask);
    const places::PlaceDescriptorIndex dindex = db.loadDescriptorIndex(index, dc);
    const bool have_cues = dindex.totalImages() > 0;
    if (!have_cues && rc.cue != "histogram") {
      std::cerr << "evaluate_places: " << db_path
                << " has no whole-image descriptors (stored before they existed; train it again "
                   "for them): the colour histograms alone are evaluated\n";
      rc.cue = "histogram";
    }

    std::vector<places::ImageHistograms> tests;
    std::vector<places::ImageDescriptors> test_descriptors;
    std::vector<std::string> truth;
    tools::forEachLabelledImage(bag, list, [&](const tools::LabelledImage& li) {
      tests.push_back(places::computeHistograms(li.bgr, hc));
      if (have_cues) test_descriptors.push_back(places::computeDescriptors(li.bgr, dc));
      truth.push_back(li.label);
    });
    if (tests.empty()) throw std::runtime_error("no labelled test image");
    std::map<std::string, std::vector<size_t>> by_place;
    for (size_t i = 0; i < truth.size(); ++i) by_place[truth[i]].push_back(i);
    for (const auto& [p, v] : by_place)
      if (index.placeIndex(p) < 0)
        std::cerr << "evaluate_places: test place '" << p << "' (" << v.size()
                  << " images) is not in the database: it counts as wrong\n";

    // Node distances of every test image for every (space, method): [combo][image][place].
    // Whole-image cues: the same, with space -1 and the cue's name.
    struct Combo {
      int space;
      Distance method;
      std::string cue;  // empty for a histogram combination
      std::vector<std::vector<double>> d;
      long single_correct = 0;
    };
    std::vector<Combo> combos;
    for (int s : spaces)
      for (Distance m : methods) combos.push_back({s, m, "", {}, 0});
    const size_t histogram_combos = combos.size();
    if (have_cues)
      for (const char* cue : {"thumbnail", "gradient", "chromaticity", "layout", "fused"})
        combos.push_back({-1, Distance::kChiSquare, cue, {}, 0});
    tools::Progress progress("evaluate_places", static_cast<long>(combos.size() * tests.size()),
                             "queries");
    long queries = 0;
    for (Combo& c : combos) {
      c.d.reserve(tests.size());
      for (size_t i = 0; i < tests.size(); ++i, progress.update(++queries)) {
        c.d.push_back(c.cue.empty() ? index.nodeDistances(c.space, c.method, tests[i])
                                    : dindex.nodeDistances(places::cueWeights(c.cue, rc.fusion),
                                                           test_descriptors[i]));
        const auto& row = c.d.back();
        const int best = static_cast<int>(std::min_element(row.begin(), row.end()) - row.begin());
        c.single_correct += index.placeNames()[best] == truth[i];
      }
    }

    // 1. The paper's protocol, one table per test place.
    YAML::Emitter y;
    y << YAML::BeginMap << YAML::Key << "database" << YAML::Value << db_path;
    y << YAML::Key << "settings" << YAML::Value << db.settings().toString();
    y << YAML::Key << "images_per_place" << YAML::Value << per_place;
    y << YAML::Key << "tables" << YAML::Value << YAML::BeginSeq;
    long places_right = 0, paper_right = 0;
    double conf_sum = 0.0;
    const auto comboName = [](const Combo& c) {
      return c.cue.empty() ? places::spaceName(c.space) + "/" + places::distanceName(c.method)
                           : c.cue;
    };
    // The combination that answers: --cue's, or (histogram) the paper's most confident.
    const Combo* cue_combo = nullptr;
    for (const Combo& c : combos)
      if (c.cue == rc.cue) cue_combo = &c;
    for (const auto& [place, idx] : by_place) {
      std::vector<size_t> chosen;
      const size_t total = idx.size(), k = std::min<size_t>(total, per_place);
      for (size_t i = 0; i < k; ++i) chosen.push_back(idx[(2 * i + 1) * total / (2 * k)]);
      std::vector<places::Recognition> recs;  // one per combination, in combos' order
      for (const Combo& c : combos) {
        std::vector<std::vector<double>> rows;
        for (size_t i : chosen) rows.push_back(c.d[i]);
        recs.push_back(places::combineTestImages(rows, c.space, c.method));
      }
      std::printf("test place %s (%zu test images)\n  %-16s", place.c_str(), chosen.size(),
                  "space");
      for (Distance m : methods) std::printf(" %-26s", places::distanceName(m).c_str());
      std::printf("\n");
      y << YAML::BeginMap << YAML::Key << "test_place" << YAML::Value << place;
      y << YAML::Key << "test_images" << YAML::Value << chosen.size();
      y << YAML::Key << "rows" << YAML::Value << YAML::BeginSeq;
      const auto emit = [&](size_t ci) {
        const places::Recognition& r = recs[ci];
        const std::string& sel = index.placeNames()[r.place];
        std::printf(" %-20s %5s", sel.c_str(), pct(r.confidence).c_str());
        y << YAML::Flow << YAML::BeginMap;
        if (combos[ci].cue.empty())
          y << YAML::Key << "space" << YAML::Value << places::spaceName(combos[ci].space)
            << YAML::Key << "method" << YAML::Value << places::distanceName(combos[ci].method);
        else
          y << YAML::Key << "cue" << YAML::Value << combos[ci].cue;
        y << YAML::Key << "selected" << YAML::Value << sel << YAML::Key << "confidence"
          << YAML::Value << r.confidence << YAML::EndMap;
      };
      for (int s : spaces) {
        std::printf("  %-16s", places::spaceName(s).c_str());
        for (size_t ci = 0; ci < histogram_combos; ++ci)
          if (combos[ci].space == s) emit(ci);
        std::printf("\n");
      }
      for (size_t ci = histogram_combos; ci < combos.size(); ++ci) {
        std::printf("  %-16s", (combos[ci].cue + " cue").c_str());
        emit(ci);
        std::printf("\n");
      }
      y << YAML::EndSeq;
      const std::vector<places::Recognition> hist_recs(recs.begin(),
                                                       recs.begin() + histogram_combos);
      const places::Recognition& paper = places::mostConfident(hist_recs);
      paper_right += index.placeNames()[paper.place] == place;
      const places::Recognition& best = cue_combo ? recs[cue_combo - combos.data()] : paper;
      const std::string& answer = index.placeNames()[best.place];
      places_right += answer == place;
      conf_sum += best.confidence;
      const std::string how =
          cue_combo ? rc.cue + " cue"
                    : places::spaceName(best.space) + ", " + places::distanceName(best.method);
      std::printf("  -> %s (%s), confidence %s: %s; the paper's rule: %s (%s, %s)\n",
                  answer.c_str(), how.c_str(), pct(best.confidence).c_str(),
                  answer == place ? "right" : "WRONG", index.placeNames()[paper.place].c_str(),
                  places::spaceName(paper.space).c_str(),
                  places::distanceName(paper.method).c_str());
      y << YAML::Key << "answer" << YAML::Value << answer << YAML::Key << "answer_by" << YAML::Value
        << how << YAML::Key << "answer_confidence" << YAML::Value << best.confidence << YAML::Key
        << "paper_answer" << YAML::Value << index.placeNames()[paper.place] << YAML::Key
        << "paper_answer_space" << YAML::Value << places::spaceName(paper.space) << YAML::Key
        << "paper_answer_method" << YAML::Value << places::distanceName(paper.method)
        << YAML::EndMap;
    }
    y << YAML::EndSeq;

    // 2. Single images.
    const Combo* best = &combos.front();  // the best histogram combination
    y << YAML::Key << "single_image_accuracy" << YAML::Value << YAML::BeginMap;
    for (size_t ci = 0; ci < combos.size(); ++ci) {
      const Combo& c = combos[ci];
      if (ci < histogram_combos && c.single_correct > best->single_correct) best = &c;
      y << YAML::Key << comboName(c) << YAML::Value
        << static_cast<double>(c.single_correct) / tests.size();
    }
    y << YAML::EndMap;
    const Combo* answering = cue_combo ? cue_combo : best;

    // 3. Sequences with --cue (histogram: the best combination): sliding window and Bayes filter.
    rc.color_space = places::spaceName(best->space);
    rc.method = places::distanceName(best->method);
    places::PlaceRecognizer recognizer(rc);
    recognizer.setDatabase(index, db.adjacencyLists(index), dindex);
    long window_right = 0, filter_right = 0;
    fs::create_directories(output);
    std::ofstream csv(fs::path(output) / "images.csv");
    csv << "image,truth,single,window,filter\n";
    for (size_t i = 0; i < tests.size(); ++i) {
      const places::PlaceResult r =
          recognizer.add(tests[i], have_cues ? &test_descriptors[i] : nullptr);
      const auto& row = answering->d[i];
      const std::string& single =
          index.placeNames()[std::min_element(row.begin(), row.end()) - row.begin()];
      const std::string& wname = index.placeNames()[r.recognition.place];
      const std::string& fname = index.placeNames()[r.filtered_place];
      window_right += wname == truth[i];
      filter_right += fname == truth[i];
      csv << i << "," << truth[i] << "," << single << "," << wname << "," << fname << "\n";
    }

    // Query speed: one image's node distances with the answering combination.
    const auto t0 = std::chrono::steady_clock::now();
    double sink = 0.0;
    int rounds = 0;
    do {
      for (size_t i = 0; i < tests.size(); ++i)
        sink += cue_combo ? dindex.nodeDistances(places::cueWeights(rc.cue, rc.fusion),
                                                 test_descriptors[i])[0]
                          : index.nodeDistances(best->space, best->method, tests[i])[0];
      ++rounds;
    } while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 0.5);
    const double qps = rounds * tests.size() /
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (sink < 0.0) std::printf(" ");

    const double n = static_cast<double>(tests.size());
    const double accuracy = static_cast<double>(places_right) / by_place.size();
    const double paper_accuracy = static_cast<double>(paper_right) / by_place.size();
    const double mean_conf = conf_sum / by_place.size();
    y << YAML::Key << "summary" << YAML::Value << YAML::BeginMap;
    y << YAML::Key << "accuracy" << YAML::Value << accuracy;
    y << YAML::Key << "mean_confidence" << YAML::Value << mean_conf;
    y << YAML::Key << "cue" << YAML::Value << rc.cue;
    y << YAML::Key << "paper_accuracy" << YAML::Value << paper_accuracy;
    y << YAML::Key << "best_space" << YAML::Value << places::spaceName(best->space);
    y << YAML::Key << "best_method" << YAML::Value << places::distanceName(best->method);
    y << YAML::Key << "histogram_single_image_accuracy" << YAML::Value << best->single_correct / n;
    y << YAML::Key << "single_image_accuracy" << YAML::Value << answering->single_correct / n;
    y << YAML::Key << "window" << YAML::Value << rc.window;
    y << YAML::Key << "window_accuracy" << YAML::Value << window_right / n;
    y << YAML::Key << "filter_accuracy" << YAML::Value << filter_right / n;
    y << YAML::Key << "queries_per_s" << YAML::Value << qps;
    y << YAML::Key << "database_images" << YAML::Value << index.totalImages(best->space);
    y << YAML::EndMap << YAML::EndMap;
    std::ofstream(fs::path(output) / "results.yaml") << y.c_str() << "\n";
    std::printf(
        "evaluate_places: accuracy=%.3f mean_confidence=%.3f cue=%s paper_accuracy=%.3f "
        "best_space=%s best_method=%s histogram_single_image_accuracy=%.3f "
        "single_image_accuracy=%.3f window_accuracy=%.3f filter_accuracy=%.3f queries_per_s=%.0f "
        "places=%zu test_images=%zu\n",
        accuracy, mean_conf, rc.cue.c_str(), paper_accuracy, places::spaceName(best->space).c_str(),
        places::distanceName(best->method).c_str(), best->single_correct / n,
        answering->single_correct / n, window_right / n, filter_right / n, qps, by_place.size(),
        tests.size());
  } catch (const std::exception& e) {
    std::cerr << "evaluate_places: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
