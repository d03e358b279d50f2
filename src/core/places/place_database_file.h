#pragma once
// Private to the place database: whether a file is one, told from its bytes before any SQLite
// connection reads it (a connection's first read rolls a hot journal back, writing the file).
#include <cstdint>
#include <string>

namespace adaptive_perception::places::file_detail {

/// Throws std::runtime_error naming `path` when its bytes show it is not a database of
/// `application_id`: no SQLite header, another application_id in the header, or, with a rollback
/// journal `journal` beside it, another one in the journal's copy of page 1 or an empty file
/// before the unfinished write. Reads only; neither file is written.
void requirePlaceDatabaseBytes(const std::string& path, const std::string& journal,
                               std::uint32_t application_id);

}  // namespace adaptive_perception::places::file_detail
