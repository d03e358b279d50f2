#pragma once
// Image lists: CSV files of `image_path,label` lines, so that users can train and evaluate on their
// own image folders. A first line `image_path,...` is a header and skipped; blank lines and lines
// starting with '#' are skipped; relative paths are relative to the CSV's folder. Labels may not
// be empty. Throws std::runtime_error naming the file and line of any problem.
#include <string>
#include <vector>

namespace adaptive_perception::io {

struct LabelledPath {
  std::string path;  // as resolved (absolute or relative to the working directory)
  std::string label;
  int line = 0;  // in the CSV, for messages
};

std::vector<LabelledPath> readImageList(const std::string& csv_path);

}  // namespace adaptive_perception::io
