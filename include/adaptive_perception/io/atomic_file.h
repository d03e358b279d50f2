#pragma once
// Writing a user's file without ever leaving it half written, and without touching any other file:
// the text goes to a new temporary file of a unique name in the same folder (mkstemp:
// `.NAME.XXXXXX`, so a user's own `NAME.tmp` is never overwritten), is flushed to disk (fsync),
// and is then renamed over PATH (atomic on one file system); the folder is synced after the rename.
#include <string>

namespace adaptive_perception::io {

/// Throws std::runtime_error naming `path` and the reason when it cannot be written (folder
/// missing or read-only, name too long, disk full); the temporary file is removed then and an
/// existing `path` is left as it was.
void writeTextFileAtomically(const std::string& path, const std::string& text);

/// The absolute, normalised form of `path` (relative to the current directory), for messages
/// that must say where a file went. Never throws.
std::string absolutePath(const std::string& path);

}  // namespace adaptive_perception::io
