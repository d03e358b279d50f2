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

/// Creates a new, empty file of a unique name beside `path` (`.NAME.XXXXXX` in its folder, by
/// mkstemp: never an existing file, never through a symlink) with the usual mode under the umask,
/// and returns its name, for a writer that fills it and then renames it over `path`. `suffix`
/// ends the name (`.NAME.XXXXXX.avi` for a writer that chooses its format by the extension; at
/// most 16 bytes, no '/': std::invalid_argument otherwise). Throws std::runtime_error naming
/// `path` and the reason when it cannot be created.
std::string createTemporaryBeside(const std::string& path, const std::string& suffix = "");

/// The absolute, normalised form of `path` (relative to the current directory), for messages
/// that must say where a file went. Never throws.
std::string absolutePath(const std::string& path);

}  // namespace adaptive_perception::io
