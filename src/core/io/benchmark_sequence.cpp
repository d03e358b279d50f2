#include "adaptive_perception/io/benchmark_sequence.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "adaptive_perception/io/image_folder.h"

namespace adaptive_perception::io {

namespace fs = std::filesystem;

std::optional<cv::Rect2d> parseGroundTruthLine(const std::string& line, bool one_based,
                                               const std::string& where) {
  std::vector<double> v;
  const char* p = line.c_str();
  while (*p) {
    while (*p == ',' || *p == ' ' || *p == '\t' || *p == '\r' || *p == ';') ++p;
    if (!*p) break;
    char* end = nullptr;
    const double x = std::strtod(p, &end);  // "nan" and "NaN" parse
    if (end == p)
      throw std::runtime_error(where + ": '" + line +
                               "' is not a box (expected 4 numbers x,y,w,h or 8 polygon corners)");
    v.push_back(x);
    p = end;
  }
  if (v.size() != 4 && v.size() != 8)
    throw std::runtime_error(where + ": " + std::to_string(v.size()) +
                             " values; expected 4 (x,y,w,h) or 8 (polygon corners)");
  for (double x : v)
    if (!std::isfinite(x)) return std::nullopt;
  cv::Rect2d box;
  if (v.size() == 4) {
    box = cv::Rect2d(v[0], v[1], v[2], v[3]);
  } else {
    const double x0 = std::min({v[0], v[2], v[4], v[6]}), x1 = std::max({v[0], v[2], v[4], v[6]});
    const double y0 = std::min({v[1], v[3], v[5], v[7]}), y1 = std::max({v[1], v[3], v[5], v[7]});
    box = cv::Rect2d(x0, y0, x1 - x0, y1 - y0);
  }
  if (!(box.width > 0 && box.height > 0)) return std::nullopt;
  if (one_based) {
    box.x -= 1.0;
    box.y -= 1.0;
  }
  return box;
}

BenchmarkSequence readBenchmarkSequence(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw std::runtime_error(dir + ": no such sequence folder");
  BenchmarkSequence seq;
  const fs::path root(dir);
  seq.name = fs::path(dir).lexically_normal().filename().string();
  if (seq.name.empty())
    seq.name = fs::path(dir).lexically_normal().parent_path().filename().string();
  fs::path images;
  bool one_based = false;
  if (fs::exists(root / "groundtruth_rect.txt") || fs::exists(root / "groundtruth_rect.1.txt")) {
    seq.format = "otb";
    one_based = true;
    seq.ground_truth_file =
        (root / (fs::exists(root / "groundtruth_rect.txt") ? "groundtruth_rect.txt"
                                                           : "groundtruth_rect.1.txt"))
            .string();
    if (fs::path(seq.ground_truth_file).filename() != "groundtruth_rect.txt")
      seq.notes.push_back("several targets: the first (groundtruth_rect.1.txt) is used");
    images = root / "img";
  } else if (fs::exists(root / "groundtruth.txt")) {
    seq.format = "vot";
    seq.ground_truth_file = (root / "groundtruth.txt").string();
    images = fs::is_directory(root / "imgs") ? root / "imgs" : root;
  } else {
    throw std::runtime_error(dir +
                             ": no ground truth: expected groundtruth_rect.txt (OTB) or "
                             "groundtruth.txt (VOT)");
  }
  if (!fs::is_directory(images)) throw std::runtime_error(images.string() + ": no such folder");
  int skipped = 0;
  seq.frames = listImages(images.string(), &skipped);
  if (seq.frames.empty())
    throw std::runtime_error(images.string() + ": no image (jpg, png, bmp, ppm, pgm)");
  if (skipped > 0 && images != root)
    seq.notes.push_back(std::to_string(skipped) + " file(s) in " + images.string() +
                        " that are not images skipped");

  std::ifstream in(seq.ground_truth_file);
  if (!in) throw std::runtime_error(seq.ground_truth_file + ": cannot open");
  std::string line;
  int line_no = 0, no_target = 0, blanks = 0;
  std::vector<std::optional<cv::Rect2d>> boxes;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) {
      ++blanks;  // blank lines at the end are common; one inside is a frame without a box
      continue;
    }
    boxes.resize(boxes.size() + blanks);
    blanks = 0;
    boxes.push_back(parseGroundTruthLine(line, one_based,
                                         seq.ground_truth_file + ":" + std::to_string(line_no)));
    no_target += !boxes.back();
  }
  if (boxes.size() > seq.frames.size()) {
    seq.notes.push_back(seq.ground_truth_file + " has " + std::to_string(boxes.size()) +
                        " boxes for " + std::to_string(seq.frames.size()) + " frames: the last " +
                        std::to_string(boxes.size() - seq.frames.size()) + " are ignored");
    boxes.resize(seq.frames.size());
  } else if (boxes.size() < seq.frames.size()) {
    seq.notes.push_back(seq.ground_truth_file + " has " + std::to_string(boxes.size()) +
                        " boxes for " + std::to_string(seq.frames.size()) + " frames: the last " +
                        std::to_string(seq.frames.size() - boxes.size()) + " have no truth");
    boxes.resize(seq.frames.size());
  }
  if (no_target > 0)
    seq.notes.push_back(std::to_string(no_target) +
                        " box(es) with NaN or zero size (target not in view): not scored");
  if (boxes.empty() || !boxes.front())
    throw std::runtime_error(seq.ground_truth_file +
                             ": the first frame has no box to start the tracker from");
  seq.truth = std::move(boxes);
  return seq;
}

}  // namespace adaptive_perception::io
