#pragma once
// evaluate_places --reference A --query B: the standard place-recognition protocol on two ordered
// traversals of one route (places/traversal_matcher.h, places/traversal_metrics.h).
//
//   evaluate_places --reference A --query B [options: evaluate_places --help]
//
// A and B are folders of images (name order) or CSV lists of image paths (io/image_folder.h).
// --database F keeps the reference traversal in a place database (places/place_database.h): when F
// does not exist, A's images are described and stored there (each frame a place named frame_N,
// N from 1, joined to the next; HSV histograms, the whole-image descriptors and SIFT), written to a
// temporary file and renamed when complete; when F exists, its images are the references, in the
// order stored, and A may be left out (given, it must list the same images). F is never changed.
// Query i's true references are i - N .. i + N (N = --tolerance_frames) unless --ground_truth
// (`query_index,reference_index,tolerance`, from 1) says otherwise; a query it does not list has
// no true reference and counts as wrong. Every method runs on the same frames; the table lists
// each, the summary line gives --method's. Writes DIR/results.yaml, DIR/queries.csv (per query and
// method: truth, best reference, confidence, right) and DIR/pr_curves.csv (one row per point and
// method); scripts/plot_places.py DIR draws DIR/pr_curve.png from them.
// Last line: `evaluate_places: mode=traversal method=.. recall_at_1=.. recall_at_5=.. pr_auc=..
// recall_at_full_precision=.. queries=.. queries_per_s=.. match_ms=.. references=..`
// (queries_per_s: descriptors and matching of one query, one core; match_ms: the matching alone).
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_perception/io/image_folder.h"
#include "adaptive_perception/places/feature_index.h"
#include "adaptive_perception/places/place_database.h"
#include "adaptive_perception/places/traversal_matcher.h"
#include "adaptive_perception/places/traversal_metrics.h"
#include "progress.h"
#include "command_line.h"

namespace adaptive_perception::tools {

namespace traversal_detail {
inline std::runtime_error unreadable(const std::string& path, const std::string& which) {
  return std::runtime_error(which + " image '" + path +
                            "' cannot be read (missing or not an image)");
}
inline cv::Mat readImage(const std::string& path, const std::string& which) {
  cv::Mat img = cv::imread(path, cv::IMREAD_COLOR);
  if (img.empty()) throw unreadable(path, which);
  return img;
}
// Every cue of one image: the whole-image descriptors and the SIFT descriptors of the words.
inline places::ImageDescriptors describe(const cv::Mat& img,
                                         const places::GlobalDescriptorConfig& config) {
  places::ImageDescriptors d = places::computeDescriptors(img, config);
  d.sift = places::extractSift(img, places::SiftConfig());
  return d;
}

// The bag of words of the references, unless none of them has a SIFT keypoint (then the words
// method is left out).
inline void learnWordsIfAny(places::ReferenceTraversal& refs, const std::vector<cv::Mat>& sift) {
  for (const cv::Mat& f : sift)
    if (f.rows > 0) return refs.learnWords(sift);
  std::cerr << "evaluate_places: no reference image has a SIFT keypoint; the words method is "
               "left out\n";
}

// The references from an existing database; with A's list too, both must name the same images.
inline places::ReferenceTraversal loadReferences(const std::string& db_path,
                                                 const std::vector<std::string>& ref_files,
                                                 const places::GlobalDescriptorConfig& config) {
  const places::PlaceDatabase db = places::PlaceDatabase::open(db_path, /*read_only=*/true);
  std::vector<std::string> sources;
  std::vector<long> ids;
  places::ReferenceTraversal refs = db.loadTraversal(config, &sources, &ids);
  if (refs.size() == 0)
    throw std::runtime_error(
        db_path + ": holds no image with whole-image descriptors (" +
        std::to_string(db.imageCount()) +
        " images): it is not a reference traversal; name a new file to build one");
  // The words' SIFT descriptors, by image id (an image without keypoints has none stored).
  std::map<long, size_t> row_of;
  for (size_t i = 0; i < ids.size(); ++i) row_of[ids[i]] = i;
  std::vector<cv::Mat> sift(ids.size(), cv::Mat(0, 128, CV_32F));
  for (const places::TrainingFrame& f : db.loadFrames()) {
    const auto it = row_of.find(f.image_id);
    if (it != row_of.end()) sift[it->second] = f.features;
  }
  learnWordsIfAny(refs, sift);
  if (!ref_files.empty()) {
    if (ref_files.size() != sources.size())
      throw std::runtime_error(db_path + " holds " + std::to_string(sources.size()) +
                               " reference images, --reference lists " +
                               std::to_string(ref_files.size()) +
                               ": leave --reference out to use the stored ones");
    for (size_t i = 0; i < sources.size(); ++i)
      if (sources[i] != ref_files[i])
        throw std::runtime_error(db_path + ": reference " + std::to_string(i + 1) + " is '" +
                                 sources[i] + "', --reference lists '" + ref_files[i] + "'");
  }
  return refs;
}

// Describes A's images; with a database path, stores them in a new database there (temporary
// file, renamed when complete, so that a failure leaves nothing behind).
inline places::ReferenceTraversal describeReferences(const std::vector<std::string>& ref_files,
                                                     const places::GlobalDescriptorConfig& config,
                                                     const std::string& db_path) {
  namespace fs = std::filesystem;
  places::ReferenceTraversal refs(config);
  std::optional<places::PlaceDatabase> db;
  const std::string tmp = db_path.empty() ? "" : db_path + ".partial-" + std::to_string(::getpid());
  struct RemoveOnFailure {
    const std::string& path;
    bool keep = false;
    ~RemoveOnFailure() {
      std::error_code ec;
      if (keep || path.empty()) return;
      fs::remove(path, ec);
      fs::remove(path + "-journal", ec);
    }
  } cleanup{tmp};
  places::DatabaseSettings settings;
  settings.spaces = {places::spaceIndex("hsv")};
  if (!tmp.empty()) {
    db.emplace(places::PlaceDatabase::create(tmp, settings));
    db->useDescriptors(config);
    db->beginBatch();
  }
  std::string previous;
  std::vector<cv::Mat> sift;
  tools::Progress progress("reference", static_cast<long>(ref_files.size()), "images");
  for (size_t i = 0; i < ref_files.size(); ++i) {
    progress.update(static_cast<long>(i) + 1);
    const cv::Mat img = readImage(ref_files[i], "reference");
    places::TrainingImage ti;
    ti.source = ref_files[i];
    ti.descriptors = describe(img, config);
    refs.add(ti.descriptors);
    sift.push_back(ti.descriptors.sift);
    ti.features = ti.descriptors.sift;
    if (!db) continue;
    ti.histograms = places::computeHistograms(img, settings.histogramConfig());
    const std::string place = "frame_" + std::to_string(i + 1);
    db->addImages(place, {ti});
    if (!previous.empty()) db->setAdjacent(previous, place);
    previous = place;
  }
  learnWordsIfAny(refs, sift);
  if (db) {
    db->commitBatch();
    db.reset();  // closed before it is renamed
    if (fs::exists(db_path))
      throw std::runtime_error(db_path +
                               " appeared while the references were being described; "
                               "it was left as it is");
    fs::rename(tmp, db_path);
    cleanup.keep = true;
  }
  return refs;
}
}  // namespace traversal_detail

/// The traversal protocol's own options; --database, --output and the fusion weights are
/// evaluate_places's, shared with the paper's protocol.
struct TraversalOptions {
  std::string reference, query, ground_truth;
  long tolerance_frames = 1;
  places::TraversalMatcherConfig matcher;
};

inline void addTraversalOptions(CommandLine& cli, TraversalOptions* o) {
  const std::string group = "Two traversals (--reference and --query)";
  places::TraversalMatcherConfig& m = o->matcher;
  cli.option("reference", &o->reference, "reference traversal: folder of images or CSV list")
      ->group(group);
  cli.option("query", &o->query, "query traversal: folder of images or CSV list")->group(group);
  cli.option("tolerance_frames", &o->tolerance_frames, config::closed(0, 1e9),
             "query i's true references: i - N .. i + N, frames")
      ->group(group);
  cli.option("ground_truth", &o->ground_truth,
             "CSV query_index,reference_index,tolerance (from 1) instead of the same index")
      ->group(group);
  cli.option("method", &m.method,
             "method of the summary line: thumbnail, gradient, chromaticity, layout, words, "
             "fused, sequence or route")
      ->group(group);
  cli.option("sequence_frames", &m.sequence.sequence_frames, "frames of a sequence match")
      ->group(group);
  cli.option("min_velocity", &m.sequence.min_velocity, "slowest sequence slope, references per query")
      ->group(group);
  cli.option("max_velocity", &m.sequence.max_velocity, "fastest sequence slope, references per query")
      ->group(group);
  cli.option("velocity_steps", &m.sequence.velocity_steps, "slopes tried between the two")
      ->group(group);
  cli.option("route_likelihood_gain", &m.route.likelihood_gain,
             "route filter: likelihood exp(-gain * enhanced distance)")
      ->group(group);
  cli.option("route_speed_change_probability", &m.route.speed_change_probability,
             "route filter: probability that the query's speed changes, per frame")
      ->group(group);
  cli.option("route_stop_probability", &m.route.stop_probability,
             "route filter: probability that a moving query stands still, per frame")
      ->group(group);
  cli.option("route_start_probability", &m.route.start_probability,
             "route filter: probability that a still query drives off, per frame")
      ->group(group);
  cli.option("route_hub_prior_queries", &m.route.hub_prior_queries,
             "route filter: prior weight of each reference's distance statistics (0: off)")
      ->group(group);
  cli.option("route_contrast_window_frames", &m.route.contrast_window_frames,
             "route filter: contrast enhancement window (0: none)")
      ->group(group);
  cli.option("route_jump_probability", &m.route.jump_probability,
             "route filter: probability of a jump anywhere, per query frame")
      ->group(group);
  cli.option("route_speed_steps", &m.route.speed_steps,
             "route filter: forward speeds, log-spaced over the filter's speed range")
      ->group(group);
}

/// Runs the protocol; `db_path`, `output` and `fusion` as evaluate_places read them.
inline int runTraversalEvaluation(CommandLine& cli, TraversalOptions opts,
                                  const places::FusionWeights& fusion, const std::string& db_path,
                                  const std::string& output) {
  namespace fs = std::filesystem;
  const std::string& ref_path = opts.reference;
  const std::string& query_path = opts.query;
  const long tolerance = opts.tolerance_frames;
  const std::string& gt_path = opts.ground_truth;
  places::TraversalMatcherConfig& cfg = opts.matcher;
  cfg.fusion = fusion;
  const bool stored = !db_path.empty() && std::filesystem::exists(db_path);
  if (query_path.empty() || (ref_path.empty() && !stored))
    cli.fail(
        "traversal mode needs --query B and --reference A (or --database F naming an "
        "existing reference traversal)");
  try {
    cfg.validate();
    const std::vector<std::string> listed =
        ref_path.empty() ? std::vector<std::string>() : io::readTraversal(ref_path);
    const std::vector<std::string> query_files = io::readTraversal(query_path);
    // What can be checked without decoding is checked before the references are described (the
    // long part): a missing file or a malformed ground-truth line is named at once.
    // (A stored traversal's listed files are only compared with the stored names, not read.)
    std::error_code ec;
    if (!stored)
      for (const std::string& f : listed)
        if (!fs::is_regular_file(f, ec)) throw traversal_detail::unreadable(f, "reference");
    for (const std::string& f : query_files)
      if (!fs::is_regular_file(f, ec)) throw traversal_detail::unreadable(f, "query");
    const std::vector<io::FrameCorrespondence> correspondences =
        gt_path.empty() ? std::vector<io::FrameCorrespondence>()
                        : io::readFrameCorrespondences(gt_path);
    const auto check_range = [&](size_t n_refs) {
      for (const io::FrameCorrespondence& c : correspondences)
        if (c.query >= static_cast<int>(query_files.size()) ||
            c.reference >= static_cast<int>(n_refs))
          throw std::runtime_error(gt_path + ": query " + std::to_string(c.query + 1) +
                                   " / reference " + std::to_string(c.reference + 1) +
                                   " beyond the traversals (" + std::to_string(query_files.size()) +
                                   " queries, " + std::to_string(n_refs) + " references)");
    };
    if (!stored) check_range(listed.size());  // a described traversal has one reference a file
    const auto t_ref = std::chrono::steady_clock::now();
    const places::ReferenceTraversal refs =
        stored ? traversal_detail::loadReferences(db_path, listed, cfg.descriptor)
               : traversal_detail::describeReferences(listed, cfg.descriptor, db_path);
    const double ref_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t_ref).count();
    const size_t n_refs = static_cast<size_t>(refs.size());
    std::vector<io::FrameCorrespondence> truth(query_files.size(),
                                               {0, -1, static_cast<int>(tolerance)});
    for (size_t i = 0; i < truth.size(); ++i) {
      truth[i].query = static_cast<int>(i);
      truth[i].reference = i < n_refs ? static_cast<int>(i) : -1;
    }
    if (!gt_path.empty()) {
      for (auto& t : truth) t.reference = -1;
      check_range(n_refs);
      for (const io::FrameCorrespondence& c : correspondences) truth[c.query] = c;
    }
    long without_truth = 0;
    for (const auto& t : truth) without_truth += t.reference < 0;
    if (without_truth > 0)
      std::cerr << "evaluate_places: " << without_truth
                << " queries have no true reference (they count as wrong)\n";

    std::printf("evaluate_places: %d reference images (%s) in %.1f s, %zu queries (%s)\n",
                refs.size(), stored ? db_path.c_str() : ref_path.c_str(), ref_s, query_files.size(),
                query_path.c_str());

    std::vector<std::string> methods = {"thumbnail", "gradient", "chromaticity", "layout",
                                        "words",     "fused",    "sequence", "route"};
    if (!refs.words()) {
      if (cfg.method == "words")
        throw std::runtime_error("--method words: no reference image has a SIFT keypoint");
      methods.erase(std::find(methods.begin(), methods.end(), "words"));
    }
    std::vector<places::TraversalMatcher> matchers;
    for (const std::string& m : methods) {
      places::TraversalMatcherConfig c = cfg;
      c.method = m;
      matchers.emplace_back(refs, c);
    }
    std::vector<std::vector<places::QueryOutcome>> outcomes(methods.size());
    std::vector<double> match_s(methods.size(), 0.0);
    double describe_s = 0.0, sift_s = 0.0;  // the whole-image descriptors; SIFT (words only)
    tools::Progress progress("queries", static_cast<long>(query_files.size()), "images");
    for (size_t i = 0; i < query_files.size(); ++i) {
      progress.update(static_cast<long>(i) + 1);
      const auto t0 = std::chrono::steady_clock::now();
      const cv::Mat img = traversal_detail::readImage(query_files[i], "query");
      places::ImageDescriptors d = places::computeDescriptors(img, cfg.descriptor);
      const auto t_sift = std::chrono::steady_clock::now();
      d.sift = places::extractSift(img, places::SiftConfig());
      const auto t_end = std::chrono::steady_clock::now();
      describe_s += std::chrono::duration<double>(t_sift - t0).count();
      sift_s += std::chrono::duration<double>(t_end - t_sift).count();
      for (size_t m = 0; m < methods.size(); ++m) {
        const auto t1 = std::chrono::steady_clock::now();
        const std::vector<float>& s = matchers[m].add(d);
        places::QueryOutcome o;
        o.ranked = places::smallestK(s, 5);
        o.confidence = matchers[m].confidence();
        match_s[m] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
        o.truth_reference = truth[i].reference;
        o.tolerance = truth[i].tolerance;
        outcomes[m].push_back(std::move(o));
      }
    }

    fs::create_directories(output);
    std::ofstream qcsv(fs::path(output) / "queries.csv");
    qcsv << "method,query,truth,tolerance,best,confidence,right\n";
    std::ofstream pcsv(fs::path(output) / "pr_curves.csv");
    pcsv << "method,threshold,precision,recall\n";
    YAML::Emitter y;
    y << YAML::BeginMap << YAML::Key << "reference" << YAML::Value << (stored ? db_path : ref_path);
    y << YAML::Key << "query" << YAML::Value << query_path;
    y << YAML::Key << "tolerance_frames" << YAML::Value << tolerance;
    y << YAML::Key << "ground_truth" << YAML::Value << (gt_path.empty() ? "same index" : gt_path);
    y << YAML::Key << "sequence_frames" << YAML::Value << cfg.sequence.sequence_frames;
    y << YAML::Key << "methods" << YAML::Value << YAML::BeginMap;
    std::printf("  %-13s %9s %9s %7s %12s %9s\n", "method", "recall@1", "recall@5", "pr_auc",
                "r@100%prec", "match_ms");
    places::TraversalMetrics chosen;
    double chosen_match_ms = 0.0;
    const double nq = static_cast<double>(query_files.size());
    for (size_t m = 0; m < methods.size(); ++m) {
      const places::TraversalMetrics r = places::scoreTraversal(outcomes[m]);
      const double ms = 1000.0 * match_s[m] / nq;
      std::printf("  %-13s %9.3f %9.3f %7.3f %12.3f %9.3f%s\n", methods[m].c_str(), r.recall_at_1,
                  r.recall_at_5, r.pr_auc, r.recall_at_full_precision, ms,
                  methods[m] == cfg.method ? "  <- --method" : "");
      for (size_t i = 0; i < outcomes[m].size(); ++i) {
        const auto& o = outcomes[m][i];
        qcsv << methods[m] << "," << i + 1 << "," << (o.truth_reference + 1) << "," << o.tolerance
             << "," << o.ranked[0] + 1 << "," << o.confidence << "," << o.rightAt(1) << "\n";
      }
      for (const auto& p : r.curve)
        pcsv << methods[m] << "," << p.threshold << "," << p.precision << "," << p.recall << "\n";
      y << YAML::Key << methods[m] << YAML::Value << YAML::BeginMap;
      y << YAML::Key << "recall_at_1" << YAML::Value << r.recall_at_1;
      y << YAML::Key << "recall_at_5" << YAML::Value << r.recall_at_5;
      y << YAML::Key << "pr_auc" << YAML::Value << r.pr_auc;
      y << YAML::Key << "recall_at_full_precision" << YAML::Value << r.recall_at_full_precision;
      y << YAML::Key << "match_ms" << YAML::Value << ms << YAML::EndMap;
      if (methods[m] == cfg.method) {
        chosen = r;
        chosen_match_ms = ms;
      }
    }
    y << YAML::EndMap;
    const bool uses_words =
        cfg.method == "words" ||
        ((cfg.method == "fused" || cfg.method == "sequence" || cfg.method == "route") &&
         cfg.fusion.words > 0);
    const double qps =
        nq / (describe_s + (uses_words ? sift_s : 0.0) + chosen_match_ms * nq / 1000.0);
    y << YAML::Key << "queries" << YAML::Value << query_files.size();
    y << YAML::Key << "references" << YAML::Value << refs.size();
    y << YAML::Key << "queries_per_s" << YAML::Value << qps << YAML::EndMap;
    std::ofstream(fs::path(output) / "results.yaml") << y.c_str() << "\n";
    qcsv.close();
    pcsv.close();
    std::printf(
        "evaluate_places: mode=traversal method=%s recall_at_1=%.3f recall_at_5=%.3f pr_auc=%.3f "
        "recall_at_full_precision=%.3f queries=%zu queries_per_s=%.1f match_ms=%.3f "
        "references=%d\n",
        cfg.method.c_str(), chosen.recall_at_1, chosen.recall_at_5, chosen.pr_auc,
        chosen.recall_at_full_precision, query_files.size(), qps, chosen_match_ms, refs.size());
  } catch (const std::exception& e) {
    std::cerr << "evaluate_places: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace adaptive_perception::tools
