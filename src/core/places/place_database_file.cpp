// A place database's identity read from its bytes (place_database_file.h).
#include "place_database_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <vector>

namespace adaptive_perception::places::file_detail {
namespace {

// What a file is, read from its bytes before any SQLite connection sees it: the first read of a
// connection rolls a hot journal back, which writes the file and removes the journal. Offsets
// and fields are SQLite's file format (sqlite.org/fileformat.html): the database header, and the
// rollback journal (a header per segment: magic, record count, checksum nonce, original size in
// pages, sector size, page size; then records: page number, the page's original bytes,
// checksum).
constexpr unsigned char kSqliteMagic[16] = {'S', 'Q', 'L', 'i', 't', 'e', ' ', 'f',
                                            'o', 'r', 'm', 'a', 't', ' ', '3', '\0'};
constexpr unsigned char kJournalMagic[8] = {0xd9, 0xd5, 0x05, 0xf9, 0x20, 0xa1, 0x63, 0xd7};
constexpr std::uint64_t kApplicationIdOffset = 68;  // in the database header (page 1)

std::uint32_t bigEndian32(const unsigned char* p) {
  return static_cast<std::uint32_t>(p[0]) << 24 | static_cast<std::uint32_t>(p[1]) << 16 |
         static_cast<std::uint32_t>(p[2]) << 8 | p[3];
}

// A file opened for reading only, closed with the object.
class ReadOnlyFile {
 public:
  explicit ReadOnlyFile(const std::string& path)
      : fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {}
  ~ReadOnlyFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  ReadOnlyFile(const ReadOnlyFile&) = delete;
  ReadOnlyFile& operator=(const ReadOnlyFile&) = delete;
  bool isOpen() const { return fd_ >= 0; }
  std::uint64_t size() const {
    struct stat st {};
    return ::fstat(fd_, &st) == 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
  }
  // False when the file ends (or a read fails) before `n` bytes.
  bool read(std::uint64_t offset, void* buf, std::size_t n) const {
    auto* out = static_cast<unsigned char*>(buf);
    while (n > 0) {
      const ssize_t got = ::pread(fd_, out, n, static_cast<off_t>(offset));
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) return false;
      out += got;
      offset += static_cast<std::uint64_t>(got);
      n -= static_cast<std::size_t>(got);
    }
    return true;
  }

 private:
  int fd_;
};

// What a rollback journal says of the database before the write it belongs to.
struct JournalOriginal {
  bool was_empty = false;                       // its rollback would leave an empty file
  std::optional<std::uint32_t> application_id;  // from the journal's copy of page 1, if any
};

// Walks the journal the way SQLite plays a hot one back (pager.c, pager_playback): segment by
// segment, each header at a multiple of the sector size, up to the first record that ends the
// playback (page 0, a short read, a checksum that fails on page 1); the first copy of page 1 is
// the original. It checks no other record's checksum, so it may take a copy of page 1 that SQLite
// would stop before: the caller requires the file's own page 1 to be ours too, so that can only
// refuse more.
JournalOriginal readJournalOriginal(const ReadOnlyFile& journal, std::uint32_t db_page_size) {
  JournalOriginal out;
  const std::uint64_t size = journal.size();
  std::uint64_t sector = 0, page = 0, off = 0;
  unsigned char hdr[28];
  for (bool first = true; off + sizeof(hdr) <= size; first = false) {
    if (!journal.read(off, hdr, sizeof(hdr)) ||
        std::memcmp(hdr, kJournalMagic, sizeof(kJournalMagic)) != 0)
      break;
    std::uint64_t records = bigEndian32(hdr + 8);
    const std::uint32_t nonce = bigEndian32(hdr + 12);
    if (first) {
      sector = bigEndian32(hdr + 20);
      page = bigEndian32(hdr + 24);
      if (page == 0) page = db_page_size;
      const auto powerOfTwo = [](std::uint64_t v) { return (v & (v - 1)) == 0; };
      // SQLite plays back nothing of a journal with sizes it does not take.
      if (page < 512 || page > 65536 || !powerOfTwo(page) || sector < 32 || sector > 65536 ||
          !powerOfTwo(sector))
        break;
      // The size in pages the file had, to which SQLite truncates it first.
      out.was_empty = bigEndian32(hdr + 16) == 0;
    }
    off += sector;
    const std::uint64_t record = page + 8;
    if (records == 0xffffffff) records = off < size ? (size - off) / record : 0;
    for (std::uint64_t r = 0; r < records; ++r, off += record) {
      unsigned char pgno[4];
      if (off + record > size || !journal.read(off, pgno, 4) || bigEndian32(pgno) == 0) return out;
      if (bigEndian32(pgno) != 1) continue;
      std::vector<unsigned char> data(page + 4);
      if (!journal.read(off + 4, data.data(), data.size())) return out;
      std::uint32_t sum = nonce;  // pager_cksum: every 200th byte from the end
      for (long i = static_cast<long>(page) - 200; i > 0; i -= 200) sum += data[i];
      if (sum != bigEndian32(data.data() + page)) return out;
      out.application_id = bigEndian32(data.data() + kApplicationIdOffset);
      return out;
    }
    off = (off + sector - 1) / sector * sector;
  }
  return out;
}

}  // namespace

// Refuses, naming the file, a file that its bytes show is not a place database: no SQLite
// header, another application_id in the header, or (with a rollback journal beside it) another
// one in the journal's copy of page 1 or an empty file before the write. Neither the file nor the
// journal is written: this runs before SQLite opens the file.
void requirePlaceDatabaseBytes(const std::string& path, const std::string& journal,
                               std::uint32_t application_id) {
  const ReadOnlyFile db(path);
  if (!db.isOpen()) throw std::runtime_error(path + ": cannot open: " + std::strerror(errno));
  const ReadOnlyFile j(journal);
  const bool has_journal = j.isOpen() && j.size() > 0;
  const std::string left = has_journal ? "; it and the journal of an unfinished write to it (" +
                                             journal + ") are left untouched"
                                       : "; it is left untouched";
  unsigned char header[100];
  if (!db.read(0, header, sizeof(header)) ||
      std::memcmp(header, kSqliteMagic, sizeof(kSqliteMagic)) != 0)
    throw std::runtime_error(path + ": not a place database (not an SQLite file)" + left);
  const std::uint32_t on_disk = bigEndian32(header + kApplicationIdOffset);
  const auto foreign = [&](std::uint32_t id, const std::string& when) {
    return std::runtime_error(path +
                              ": an SQLite file but not an adaptive_perception place database "
                              "(application_id " +
                              std::to_string(id) + when + ")" + left);
  };
  if (on_disk != application_id) throw foreign(on_disk, "");
  if (!has_journal) return;
  const std::uint32_t page_size = header[16] << 8 | header[17];  // 1 stands for 65536
  const JournalOriginal original = readJournalOriginal(j, page_size == 1 ? 65536 : page_size);
  if (original.was_empty)
    throw std::runtime_error(path +
                             ": not a place database (empty before the unfinished write, which "
                             "never made it one)" +
                             left);
  if (original.application_id && *original.application_id != on_disk)
    throw foreign(*original.application_id, " before the unfinished write");
}

}  // namespace adaptive_perception::places::file_detail
