#pragma once
// Single-object tracking sequences as the two standard benchmarks ship them, read in place:
//
//   OTB  DIR/img/NNNN.jpg (numbering may start above 1) and DIR/groundtruth_rect.txt (else
//        groundtruth_rect.1.txt): one `x y w h` line per frame, 1-based pixels, separated by
//        commas, tabs or spaces.
//   VOT  DIR/imgs/NNNNNNNN.jpg, or the images beside DIR/groundtruth.txt: one line per frame,
//        `x,y,w,h` or the 8 corners of a rotated rectangle (taken as their axis-aligned bounding
//        box, as box trackers are scored), 0-based pixels.
//
// Frames are the folder's images (jpg, jpeg, png, bmp, ppm, pgm; any case) in natural name order;
// other files (Thumbs.db, attrs.txt) are skipped and noted. Ground truth line k belongs to frame k.
// A box with a NaN, a zero or negative size (VOT marks a target out of view so) gives that frame
// no truth; a file longer or shorter than the frames is cut or leaves the last frames without
// truth. Each of these is reported in `notes`. A missing folder, no image, no ground-truth file, or
// a line that is not 4 or 8 numbers throws std::runtime_error naming the file (and line).
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace adaptive_perception::io {

struct BenchmarkSequence {
  std::string name;    // the folder's name
  std::string format;  // "otb" or "vot"
  std::string ground_truth_file;
  std::vector<std::string> frames;               // image paths in order
  std::vector<std::optional<cv::Rect2d>> truth;  // per frame, 0-based pixels; nullopt: none
  std::vector<std::string> notes;                // what was skipped or cut, for the user
};

BenchmarkSequence readBenchmarkSequence(const std::string& dir);

/// One ground-truth line as a 0-based axis-aligned box; nullopt for a box without a target (NaN,
/// zero or negative size). `one_based` subtracts 1 from x and y (OTB). Throws std::runtime_error
/// `where: ...` when the line is not 4 or 8 numbers.
std::optional<cv::Rect2d> parseGroundTruthLine(const std::string& line, bool one_based,
                                               const std::string& where);

}  // namespace adaptive_perception::io
