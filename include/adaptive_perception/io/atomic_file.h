#pragma once
// Writing a user's file without ever leaving it half written: the text goes to PATH.tmp, which is
// then renamed over PATH (atomic on one file system).
#include <string>

namespace adaptive_perception::io {

/// Throws std::runtime_error naming `path` when it cannot be written; the temporary file is
/// removed then and an existing `path` is left as it was.
void writeTextFileAtomically(const std::string& path, const std::string& text);

}  // namespace adaptive_perception::io
