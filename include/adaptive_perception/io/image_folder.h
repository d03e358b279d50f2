#pragma once
// Ordered image traversals as place-recognition benchmarks ship them, read in place:
//
//   a folder   its images (jpg, jpeg, png, bmp, ppm, pgm; any case) in natural name order
//              ("9.jpg" before "10.jpg", "images-00010.png" before "images-00020.png"); other
//              files (Thumbs.db, README.md) are skipped and counted;
//   a CSV      one image path per line in its first column (further columns are ignored); a first
//              line starting `image_path` is a header; blank lines and '#' lines are skipped;
//              relative paths are relative to the CSV's folder.
//
// Frame correspondences between two traversals (Nordland's sample_ground_truth.csv):
// `query_index,reference_index,tolerance` per line, indices counting from 1, a header line of
// words allowed. Every problem throws std::runtime_error naming the file (and line).
#include <string>
#include <vector>

namespace adaptive_perception::io {

/// `s` without leading and trailing spaces, tabs and carriage returns (CSV fields, CRLF files).
std::string trimmed(const std::string& s);

/// One line of a small CSV file that holds data: its number (from 1) and its text, trimmed.
struct CsvLine {
  int number = 0;
  std::string text;
};
/// The lines of `path` that hold data (blank lines and `#` comments left out). Throws
/// "`path`: `cannot_open`" when the file cannot be read.
std::vector<CsvLine> readCsvLines(const std::string& path, const std::string& cannot_open);
/// A path as a list names it: absolute as it is, else relative to the list's folder.
std::string besideList(const std::string& list_path, const std::string& path);

/// True for the image extensions above.
bool isImageFile(const std::string& path);
/// Natural order: runs of digits compare by value.
bool naturalLess(const std::string& a, const std::string& b);
/// The images of a folder in natural name order; `skipped` (if given) receives the number of other
/// regular files. Throws when the folder does not exist.
std::vector<std::string> listImages(const std::string& dir, int* skipped = nullptr);

/// A traversal: a folder or a CSV list as above. Throws when it has no image.
std::vector<std::string> readTraversal(const std::string& folder_or_csv);

/// One query's true reference frames: reference_index +- tolerance (0-based indices).
struct FrameCorrespondence {
  int query = 0;
  int reference = 0;
  int tolerance = 0;
};

/// Reads `query_index,reference_index,tolerance` lines (1-based in the file, 0-based out).
/// Negative or zero indices, a negative tolerance or a line that is not three integers throw
/// `file:line: ...`.
std::vector<FrameCorrespondence> readFrameCorrespondences(const std::string& csv_path);

}  // namespace adaptive_perception::io
