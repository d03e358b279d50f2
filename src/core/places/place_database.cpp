#include "adaptive_perception/places/place_database.h"

#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <vector>

#include "place_database_file.h"
#include "sqlite_statement.h"

namespace adaptive_perception::places {
namespace {

using sqlite_detail::Statement;
using sqlite_detail::Transaction;

constexpr int kApplicationId = 0x41505043;  // "APPC"
constexpr int kSchemaVersion = 1;
constexpr const char* kFormat = "adaptive_perception.places";
// Per-image extras; created with a new database and added to an older one opened for writing.
constexpr const char* kOptionalTables =
    "CREATE TABLE IF NOT EXISTS features (image_id INTEGER PRIMARY KEY, rows INTEGER NOT NULL, "
    "data BLOB NOT NULL);"
    "CREATE TABLE IF NOT EXISTS poses (image_id INTEGER PRIMARY KEY, x_m REAL NOT NULL, y_m REAL "
    "NOT NULL, yaw_rad REAL NOT NULL);"
    "CREATE TABLE IF NOT EXISTS structure (image_id INTEGER PRIMARY KEY, data BLOB NOT NULL);"
    "CREATE TABLE IF NOT EXISTS descriptors (image_id INTEGER NOT NULL, kind INTEGER NOT NULL, "
    "data BLOB NOT NULL, PRIMARY KEY (image_id, kind));";

sqlite3* openRaw(const std::string& path, int flags) {
  sqlite3* db = nullptr;
  const int rc = sqlite3_open_v2(path.c_str(), &db, flags, nullptr);
  if (rc != SQLITE_OK) {
    const std::string msg = db ? sqlite3_errmsg(db) : sqlite3_errstr(rc);
    sqlite3_close(db);
    throw std::runtime_error(path + ": cannot open as a place database: " + msg);
  }
  sqlite3_busy_timeout(db, 5000);
  sqlite3_extended_result_codes(db, 1);
  return db;
}

}  // namespace

HistogramConfig DatabaseSettings::histogramConfig() const {
  HistogramConfig c;
  c.bins = bins;
  c.spaces = spaces;
  c.mask = mask;
  return c;
}

DatabaseSettings DatabaseSettings::fromHistogramConfig(const HistogramConfig& c) {
  DatabaseSettings s;
  s.bins = c.bins;
  s.spaces = c.spaces;
  std::sort(s.spaces.begin(), s.spaces.end());
  s.spaces.erase(std::unique(s.spaces.begin(), s.spaces.end()), s.spaces.end());
  s.mask = c.mask;
  return s;
}

std::string DatabaseSettings::toString() const {
  return "bins=" + std::to_string(bins) + " spaces=" + spacesToString(spaces) +
         " mask=" + mask.toString();
}

PlaceDatabase::PlaceDatabase(sqlite3* db, std::string path, bool read_only)
    : db_(db), path_(std::move(path)), read_only_(read_only) {}

PlaceDatabase::PlaceDatabase(PlaceDatabase&& o) noexcept
    : db_(o.db_),
      path_(std::move(o.path_)),
      read_only_(o.read_only_),
      in_batch_(o.in_batch_),
      recovered_journal_(o.recovered_journal_),
      settings_(o.settings_),
      descriptor_settings_(std::move(o.descriptor_settings_)) {
  o.db_ = nullptr;
  o.in_batch_ = false;
}

PlaceDatabase& PlaceDatabase::operator=(PlaceDatabase&& o) noexcept {
  if (this != &o) {
    if (db_ && in_batch_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    sqlite3_close(db_);
    db_ = o.db_;
    o.db_ = nullptr;
    path_ = std::move(o.path_);
    read_only_ = o.read_only_;
    in_batch_ = o.in_batch_;
    o.in_batch_ = false;
    recovered_journal_ = o.recovered_journal_;
    settings_ = o.settings_;
    descriptor_settings_ = std::move(o.descriptor_settings_);
  }
  return *this;
}

PlaceDatabase::~PlaceDatabase() {
  if (db_ && in_batch_) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(db_);
}

void PlaceDatabase::beginBatch() {
  if (read_only_) throw std::runtime_error(path_ + ": opened read-only: cannot write");
  if (in_batch_) throw std::logic_error(path_ + ": beginBatch: a batch is already open");
  // No wait for another writer: it may hold the database for a whole training run.
  sqlite3_busy_timeout(db_, 0);
  char* err = nullptr;
  const int rc = sqlite3_exec(db_, "BEGIN IMMEDIATE", nullptr, nullptr, &err);
  sqlite3_free(err);
  sqlite3_busy_timeout(db_, 5000);
  if ((rc & 0xff) == SQLITE_BUSY)
    throw std::runtime_error(path_ +
                             ": another process is writing to this place database (a "
                             "train_places run or a node's add_images); try again when it has "
                             "finished");
  if (rc != SQLITE_OK)
    throw std::runtime_error(path_ + ": cannot start writing: " + sqlite3_errmsg(db_));
  in_batch_ = true;
}

void PlaceDatabase::commitBatch() {
  if (!in_batch_) throw std::logic_error(path_ + ": commitBatch: no batch is open");
  exec("COMMIT");
  in_batch_ = false;
}

int PlaceDatabase::replaceImages(const std::string& place, const std::vector<TrainingImage>& images,
                                 int* replaced) {
  Transaction t(db_, path_);
  int before = 0;
  const int pid = placeId(place, false);
  if (pid >= 0) {
    const std::string in_place =
        " WHERE image_id IN (SELECT id FROM images WHERE place_id = " + std::to_string(pid) + ");";
    Statement count(db_, "SELECT COUNT(*) FROM images WHERE place_id = ?", path_);
    count.bind(1, static_cast<long long>(pid));
    if (count.step()) before = static_cast<int>(count.integer(0));
    exec("DELETE FROM features" + in_place + "DELETE FROM poses" + in_place +
         "DELETE FROM structure" + in_place + "DELETE FROM descriptors" + in_place +
         "DELETE FROM histograms" + in_place +
         "DELETE FROM images WHERE place_id = " + std::to_string(pid) + ";");
  }
  const int added = addImages(place, images);
  t.commit();
  if (replaced) *replaced = before;
  return added;
}

void PlaceDatabase::exec(const std::string& sql) const {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string msg = err ? err : "unknown error";
    sqlite3_free(err);
    throw std::runtime_error(path_ + ": " + msg);
  }
}

PlaceDatabase PlaceDatabase::create(const std::string& path, const DatabaseSettings& settings) {
  settings.histogramConfig().validate();
  if (std::filesystem::exists(path))
    throw std::runtime_error(path +
                             ": already exists; a new place database is never written over "
                             "an existing file");
  // Build it beside the target, then link it into place: link() fails rather than replace a
  // file that appeared meanwhile, and a crash leaves at worst a stray temporary file.
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  std::filesystem::remove(tmp);
  {
    PlaceDatabase db(openRaw(tmp, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE), tmp, false);
    db.exec("PRAGMA application_id = " + std::to_string(kApplicationId));
    db.exec("PRAGMA user_version = " + std::to_string(kSchemaVersion));
    Transaction t(db.db_, tmp);
    db.exec(
        "CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);"
        "CREATE TABLE places (id INTEGER PRIMARY KEY, name TEXT NOT NULL UNIQUE);"
        "CREATE TABLE adjacency (a INTEGER NOT NULL, b INTEGER NOT NULL, PRIMARY KEY (a, b));"
        "CREATE TABLE images (id INTEGER PRIMARY KEY, place_id INTEGER NOT NULL, source TEXT, "
        "stamp_s REAL);"
        "CREATE INDEX images_by_place ON images (place_id);"
        "CREATE TABLE histograms (image_id INTEGER NOT NULL, space INTEGER NOT NULL, data BLOB "
        "NOT NULL, PRIMARY KEY (image_id, space));");
    db.exec(kOptionalTables);
    Statement meta(db.db_, "INSERT INTO meta (key, value) VALUES (?, ?)", tmp);
    const std::vector<std::pair<std::string, std::string>> kv = {
        {"format", kFormat},
        {"bins", std::to_string(settings.bins)},
        {"spaces", spacesToString(settings.spaces)},
        {"mask", settings.mask.toString()}};
    for (const auto& [k, v] : kv) {
      meta.bind(1, k).bind(2, v);
      meta.step();
      meta.reset();
    }
    t.commit();
  }
  if (::link(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::filesystem::remove(tmp);
    throw std::runtime_error(path + ": cannot create the place database: " + why);
  }
  std::filesystem::remove(tmp);
  return open(path);
}

PlaceDatabase PlaceDatabase::open(const std::string& path, bool read_only) {
  if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": no such file");
  if (!std::filesystem::is_regular_file(path))
    throw std::runtime_error(path + ": not a regular file");
  // SQLite looks for the journal beside the file the path leads to.
  std::error_code ec;
  const std::filesystem::path real = std::filesystem::canonical(path, ec);
  const std::string journal = (ec ? path : real.string()) + "-journal";
  // Before any SQLite connection reads the file: its first read would roll a hot journal back,
  // writing a file that may not be ours.
  file_detail::requirePlaceDatabaseBytes(path, journal, kApplicationId);
  // A writer killed mid-transaction leaves a hot rollback journal beside the file, which only a
  // read-write connection may roll back (a read-only one gets "attempt to write a readonly
  // database"). A reader therefore lets a short read-write connection do it first.
  bool recovered = false;
  if (read_only && std::filesystem::exists(journal, ec) &&
      std::filesystem::file_size(journal, ec) > 0) {
    sqlite3* rw = nullptr;
    try {
      rw = openRaw(path, SQLITE_OPEN_READWRITE);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(
          path + ": a write to it was interrupted (the hot journal " + journal +
          " remains) and it cannot be opened for writing to roll that back: " + e.what());
    }
    // The first read of a connection rolls a hot journal back.
    const int rc = sqlite3_exec(rw, "PRAGMA application_id", nullptr, nullptr, nullptr);
    sqlite3_close(rw);
    recovered = rc == SQLITE_OK && !std::filesystem::exists(journal, ec);
  }
  PlaceDatabase db(openRaw(path, read_only ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE), path,
                   read_only);
  db.recovered_journal_ = recovered;
  long long app_id = 0, version = 0;
  try {
    Statement q(db.db_, "PRAGMA application_id", path);
    if (q.step()) app_id = q.integer(0);
    Statement v(db.db_, "PRAGMA user_version", path);
    if (v.step()) version = v.integer(0);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": not a place database (not readable as SQLite: " +
                             std::string(e.what()).substr(path.size() + 2) + ")");
  }
  if (app_id != kApplicationId)
    throw std::runtime_error(path +
                             ": an SQLite file but not an adaptive_perception place database "
                             "(application_id " +
                             std::to_string(app_id) + "); it is left untouched");
  if (version != kSchemaVersion)
    throw std::runtime_error(path + ": place database schema version " + std::to_string(version) +
                             ", this build reads version " + std::to_string(kSchemaVersion));
  db.readSettings();
  if (!read_only) {
    db.exec("PRAGMA synchronous = FULL");
    db.exec(kOptionalTables);
  }
  return db;
}

PlaceDatabase PlaceDatabase::openOrCreate(const std::string& path,
                                          const DatabaseSettings& settings) {
  return std::filesystem::exists(path) ? open(path) : create(path, settings);
}

void PlaceDatabase::readSettings() {
  std::map<std::string, std::string> meta;
  try {
    Statement q(db_, "SELECT key, value FROM meta", path_);
    while (q.step()) meta[q.text(0)] = q.text(1);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path_ + ": damaged place database (meta table: " + e.what() + ")");
  }
  if (meta["format"] != kFormat)
    throw std::runtime_error(path_ + ": meta 'format' is '" + meta["format"] + "', expected '" +
                             kFormat + "'");
  try {
    settings_.bins = std::stoi(meta.at("bins"));
    settings_.spaces = parseSpaces(meta.at("spaces"));
    settings_.mask = MaskConfig::parse(meta.at("mask"));
    settings_.histogramConfig().validate();
  } catch (const std::exception& e) {
    throw std::runtime_error(path_ + ": damaged place database settings (" + e.what() + ")");
  }
  descriptor_settings_ = meta.count("descriptors") ? meta["descriptors"] : "";
}

void PlaceDatabase::useDescriptors(const GlobalDescriptorConfig& config) {
  const std::string wanted = config.toString();
  if (descriptor_settings_ == wanted) return;
  if (!descriptor_settings_.empty())
    throw std::runtime_error(path_ + ": its whole-image descriptors were made with " +
                             descriptor_settings_ + ", asked for " + wanted +
                             "; use those settings or build a new database");
  Transaction t(db_, path_);
  Statement meta(db_, "INSERT OR REPLACE INTO meta (key, value) VALUES ('descriptors', ?)", path_);
  meta.bind(1, wanted);
  meta.step();
  t.commit();
  descriptor_settings_ = wanted;
}

void PlaceDatabase::requireSettings(const DatabaseSettings& wanted) const {
  if (!(wanted == settings_))
    throw std::runtime_error(path_ + ": built with " + settings_.toString() + ", asked for " +
                             wanted.toString() +
                             "; use the database's settings or build a new database");
}

int PlaceDatabase::placeId(const std::string& name, bool create) {
  Statement q(db_, "SELECT id FROM places WHERE name = ?", path_);
  q.bind(1, name);
  if (q.step()) return static_cast<int>(q.integer(0));
  if (!create) return -1;
  Statement ins(db_, "INSERT INTO places (name) VALUES (?)", path_);
  ins.bind(1, name);
  ins.step();
  return static_cast<int>(sqlite3_last_insert_rowid(db_));
}

int PlaceDatabase::addImages(const std::string& place, const std::vector<TrainingImage>& images) {
  if (place.empty()) throw std::invalid_argument("addImages: empty place name");
  for (size_t i = 0; i < images.size(); ++i) {
    const ImageHistograms& h = images[i].histograms;
    if (h.bins != settings_.bins)
      throw std::invalid_argument("addImages: image " + images[i].source + " has " +
                                  std::to_string(h.bins) + " bins, the database " +
                                  std::to_string(settings_.bins));
    for (int s : settings_.spaces)
      if (static_cast<int>(h.spaces[s].size()) != 3 * settings_.bins)
        throw std::invalid_argument("addImages: image " + images[i].source + " lacks space " +
                                    spaceName(s));
    const cv::Mat& f = images[i].features;
    if (!f.empty() && (f.cols != 128 || f.type() != CV_32F))
      throw std::invalid_argument("addImages: image " + images[i].source +
                                  " has features that are not N x 128 CV_32F");
    const cv::Mat& st = images[i].structure;
    if (!st.empty() && (st.rows != 1 || st.type() != CV_32F))
      throw std::invalid_argument("addImages: image " + images[i].source +
                                  " has a line-structure descriptor that is not 1 x D CV_32F");
    const auto& rows = images[i].descriptors.rows;
    if (!rows.empty()) {
      if (descriptor_settings_.empty())
        throw std::logic_error("addImages: call useDescriptors() before storing descriptors");
      if (rows.size() != static_cast<size_t>(kNumDescriptorKinds))
        throw std::invalid_argument("addImages: image " + images[i].source +
                                    " lacks a whole-image descriptor");
      for (const cv::Mat& r : rows)
        if (r.rows != 1 || r.type() != CV_8UC1 || !r.isContinuous())
          throw std::invalid_argument("addImages: image " + images[i].source +
                                      " has a descriptor that is not one continuous 8-bit row");
    }
  }
  Transaction t(db_, path_);
  const int pid = placeId(place, true);
  Statement img(db_, "INSERT INTO images (place_id, source, stamp_s) VALUES (?, ?, ?)", path_);
  Statement hist(db_, "INSERT INTO histograms (image_id, space, data) VALUES (?, ?, ?)", path_);
  Statement feat(db_, "INSERT INTO features (image_id, rows, data) VALUES (?, ?, ?)", path_);
  Statement pose(db_, "INSERT INTO poses (image_id, x_m, y_m, yaw_rad) VALUES (?, ?, ?, ?)", path_);
  Statement structure(db_, "INSERT INTO structure (image_id, data) VALUES (?, ?)", path_);
  Statement desc(db_, "INSERT INTO descriptors (image_id, kind, data) VALUES (?, ?, ?)", path_);
  for (const TrainingImage& ti : images) {
    img.bind(1, static_cast<long long>(pid)).bind(2, ti.source).bind(3, ti.stamp_s);
    img.step();
    img.reset();
    const long long iid = sqlite3_last_insert_rowid(db_);
    for (int s : settings_.spaces) {
      const std::vector<float>& h = ti.histograms.spaces[s];
      hist.bind(1, iid).bind(2, static_cast<long long>(s));
      hist.bindBlob(3, h.data(), static_cast<int>(h.size() * sizeof(float)));
      hist.step();
      hist.reset();
    }
    if (!ti.features.empty()) {
      cv::Mat bytes;
      ti.features.convertTo(bytes, CV_8U);  // SIFT descriptors are 0..255 (rounded here)
      feat.bind(1, iid).bind(2, static_cast<long long>(bytes.rows));
      feat.bindBlob(3, bytes.data, static_cast<int>(bytes.total()));
      feat.step();
      feat.reset();
    }
    if (!ti.structure.empty()) {
      const cv::Mat st = ti.structure.isContinuous() ? ti.structure : ti.structure.clone();
      structure.bind(1, iid).bindBlob(2, st.data, static_cast<int>(st.total() * sizeof(float)));
      structure.step();
      structure.reset();
    }
    for (size_t k = 0; k < ti.descriptors.rows.size(); ++k) {
      const cv::Mat& r = ti.descriptors.rows[k];
      desc.bind(1, iid).bind(2, static_cast<long long>(k));
      desc.bindBlob(3, r.data, static_cast<int>(r.total()));
      desc.step();
      desc.reset();
    }
    if (ti.pose) {
      pose.bind(1, iid).bind(2, (*ti.pose)[0]).bind(3, (*ti.pose)[1]).bind(4, (*ti.pose)[2]);
      pose.step();
      pose.reset();
    }
  }
  t.commit();
  return static_cast<int>(images.size());
}

bool PlaceDatabase::removePlace(const std::string& place) {
  Transaction t(db_, path_);
  const int pid = placeId(place, false);
  if (pid < 0) return false;
  const std::string id = std::to_string(pid);
  exec("DELETE FROM features WHERE image_id IN (SELECT id FROM images WHERE place_id = " + id +
       ");"
       "DELETE FROM poses WHERE image_id IN (SELECT id FROM images WHERE place_id = " +
       id +
       ");"
       "DELETE FROM structure WHERE image_id IN (SELECT id FROM images WHERE place_id = " +
       id +
       ");"
       "DELETE FROM descriptors WHERE image_id IN (SELECT id FROM images WHERE place_id = " +
       id +
       ");"
       "DELETE FROM histograms WHERE image_id IN (SELECT id FROM images WHERE place_id = " +
       id +
       ");"
       "DELETE FROM images WHERE place_id = " +
       id + "; DELETE FROM adjacency WHERE a = " + id + " OR b = " + id +
       "; DELETE FROM places WHERE id = " + id + ";");
  t.commit();
  return true;
}

void PlaceDatabase::setAdjacent(const std::string& a, const std::string& b, bool connected) {
  if (a == b) throw std::invalid_argument("setAdjacent: a place is not adjacent to itself");
  Transaction t(db_, path_);
  int ia = placeId(a, false), ib = placeId(b, false);
  if (ia < 0 || ib < 0)
    throw std::invalid_argument("setAdjacent: unknown place '" + (ia < 0 ? a : b) + "'");
  if (ia > ib) std::swap(ia, ib);
  Statement q(db_,
              connected ? "INSERT OR IGNORE INTO adjacency (a, b) VALUES (?, ?)"
                        : "DELETE FROM adjacency WHERE a = ? AND b = ?",
              path_);
  q.bind(1, static_cast<long long>(ia)).bind(2, static_cast<long long>(ib));
  q.step();
  t.commit();
}

}  // namespace adaptive_perception::places
