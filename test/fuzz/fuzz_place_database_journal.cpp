// libFuzzer target: a place database with the rollback journal of an interrupted write beside it
// (places/place_database.h: open() reads both files' bytes before SQLite does and lets SQLite roll
// back only a journal of a place database). The input is the database's length (4 bytes, little
// endian, taken modulo what follows), the database, then the journal. Opened read-only and read
// whole; when open() refuses the file and says it is left untouched, both files must be as they
// were, byte for byte.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "adaptive_perception/places/place_database.h"
#include "fuzz_input.h"

using namespace adaptive_perception;

namespace {
std::string contents(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 4) return 0;
  const std::size_t rest = size - 4;
  const std::uint32_t declared = static_cast<std::uint32_t>(data[0]) | data[1] << 8 |
                                 data[2] << 16 | static_cast<std::uint32_t>(data[3]) << 24;
  const std::size_t n = declared % (rest + 1);
  const std::uint8_t* db_bytes = data + 4;
  const std::uint8_t* journal_bytes = data + 4 + n;
  const std::string path = fuzz::inputFile(db_bytes, n, ".sqlite");
  const std::string journal = fuzz::inputFile(journal_bytes, rest - n, ".sqlite-journal");
  std::string refusal;
  try {
    const auto db = places::PlaceDatabase::open(path, true);
    fuzz::parsesOrRefuses([&] {
      const places::PlaceIndex index = db.loadIndex();
      db.adjacencyLists(index);
      db.loadFrames();
      db.loadTraversal(places::GlobalDescriptorConfig());
    });
  } catch (const std::exception& e) {
    refusal = e.what();
  }
  // The refusal's own words end the message (an error may quote the file's text before them).
  const std::string untouched = "left untouched";
  if (refusal.size() >= untouched.size() &&
      refusal.compare(refusal.size() - untouched.size(), untouched.size(), untouched) == 0) {
    const std::string db_before(reinterpret_cast<const char*>(db_bytes), n);
    const std::string journal_before(reinterpret_cast<const char*>(journal_bytes), rest - n);
    std::error_code ec;
    if (contents(path) != db_before || !std::filesystem::exists(journal, ec) ||
        contents(journal) != journal_before)
      std::abort();  // said untouched, but a file changed
  }
  return 0;
}
