#pragma once
// The place database: an SQLite file holding the places, their adjacency (the topological map)
// and every training image's histograms in each configured colour space, with the histogram
// settings it was built with.
//
// Safety: every change runs in one transaction (SQLite's rollback journal, synchronous=FULL), so a
// writer killed at any point leaves the database as it was before the change or after it. A batch
// (beginBatch .. commitBatch: a whole training run) is one transaction too, and holds the write
// lock from its start: a second writer is refused at once with a message saying so.
//
// Opening checks what the file is before SQLite reads it (a connection's first read rolls a hot
// journal back, which writes the file): from its bytes alone, the SQLite header and its
// application_id, and, when a rollback journal lies beside it, the journal's copy of page 1 (the
// application_id before the unfinished write) and the size it had before. A file that is not
// SQLite, SQLite with another application_id in either place, or one that was empty before the
// write, is refused with an error naming the file and saying that it is left untouched: neither
// it nor its journal is written, read-only or not. Only a place database's hot journal is rolled
// back: by a reader first (recoveredJournal() tells), by a writer on its first read. A place
// database of an unknown schema version or without the format key is refused after that. A
// database built with other settings (bins, colour spaces, mask) is refused by requireSettings
// with both settings named. A stored value a reader cannot use (a histogram bin that is NaN,
// infinite or negative; a line-structure value or pose that is not finite) is refused when it is
// read, naming the file and the image: NaN distances would make the best place an arbitrary one.
//
// Schema (version 1): meta(key, value); places(id, name UNIQUE); adjacency(a, b) with a < b;
// images(id, place_id, source, stamp_s); histograms(image_id, space, data BLOB of 3 * bins
// little-endian float32); features(image_id, rows, data BLOB of rows x 128 uint8 SIFT
// descriptors); poses(image_id, x_m, y_m, yaw_rad); structure(image_id, data BLOB of D
// little-endian float32, line_structure.h); descriptors(image_id, kind, data BLOB of the
// global_descriptor.h row of that kind), with meta 'descriptors' holding the settings they were
// made with. The last four are optional per image (room classification, papers/002; the
// whole-image cues) and are added to an older file when it is opened for writing.
#include <array>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "adaptive_perception/places/global_descriptor.h"
#include "adaptive_perception/places/histogram.h"
#include "adaptive_perception/places/place_descriptor_index.h"
#include "adaptive_perception/places/place_matcher.h"
#include "adaptive_perception/places/traversal_matcher.h"

struct sqlite3;

namespace adaptive_perception::places {

/// What the stored histograms were computed with. Two databases (or a database and a caller)
/// agree only when all of these are equal.
struct DatabaseSettings {
  int bins = 256;
  std::vector<int> spaces{0, 1, 2, 3, 4, 5, 6, 7};
  MaskConfig mask;

  HistogramConfig histogramConfig() const;
  static DatabaseSettings fromHistogramConfig(const HistogramConfig& c);
  std::string toString() const;  // "bins=256 spaces=rgb,... mask=none"
  bool operator==(const DatabaseSettings& o) const {
    return bins == o.bins && spaces == o.spaces && mask == o.mask;
  }
};

/// One training image to store.
struct TrainingImage {
  std::string source;  // where it came from: a file path or "bag.bag@12.5"
  double stamp_s = 0.0;
  ImageHistograms histograms;    // must have every space of the settings
  cv::Mat features;              // optional: N x 128 CV_32F SIFT descriptors (stored as uint8)
  cv::Mat structure;             // optional: 1 x D CV_32F line-structure descriptor
  ImageDescriptors descriptors;  // optional: every whole-image descriptor (see useDescriptors)
  std::optional<std::array<double, 3>> pose;  // optional: x_m, y_m, yaw_rad in map
};

/// A stored training frame with SIFT features, for room classification and appearance MCL.
struct TrainingFrame {
  long image_id = 0;
  std::string place;
  cv::Mat features;   // N x 128 CV_32F
  cv::Mat structure;  // 1 x D CV_32F line-structure descriptor; empty when not stored
  bool has_pose = false;
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0;
};

struct PlaceInfo {
  std::string name;
  int images = 0;
};

class PlaceDatabase {
 public:
  /// Creates a new database at `path`; throws std::runtime_error when the file already exists
  /// (it is never replaced) or cannot be created.
  static PlaceDatabase create(const std::string& path, const DatabaseSettings& settings);
  /// Opens an existing database; throws std::runtime_error naming the file when it is missing,
  /// not SQLite, not a place database, or of an unknown schema version. A file that is no place
  /// database is refused before SQLite reads it, so a hot journal beside it is not rolled back.
  static PlaceDatabase open(const std::string& path, bool read_only = false);
  /// open() when the file exists, else create().
  static PlaceDatabase openOrCreate(const std::string& path, const DatabaseSettings& settings);

  PlaceDatabase(PlaceDatabase&& o) noexcept;
  PlaceDatabase& operator=(PlaceDatabase&& o) noexcept;
  ~PlaceDatabase();

  const std::string& path() const { return path_; }
  const DatabaseSettings& settings() const { return settings_; }
  /// Throws std::runtime_error naming both settings when `wanted` differs from the stored ones.
  void requireSettings(const DatabaseSettings& wanted) const;

  /// Declares the settings of the whole-image descriptors about to be stored: written to a
  /// database that has none yet; throws std::runtime_error naming both when it holds
  /// descriptors made with other settings.
  void useDescriptors(const GlobalDescriptorConfig& config);
  /// The settings of the stored descriptors ("" when none are stored).
  const std::string& descriptorSettings() const { return descriptor_settings_; }

  /// Adds the images to `place` (created when new) in one transaction; returns the stored count.
  /// Throws std::invalid_argument when an image lacks a space of the settings or has other bins;
  /// nothing is stored then.
  int addImages(const std::string& place, const std::vector<TrainingImage>& images);
  /// Replaces the images of `place` (created when new; its edges stay) by `images`, in one
  /// transaction; returns the stored count, and the count it had before in *replaced.
  int replaceImages(const std::string& place, const std::vector<TrainingImage>& images,
                    int* replaced = nullptr);
  /// Opens one transaction for every change until commitBatch(); a batch not committed (an
  /// exception, a kill, the database destroyed) leaves the database as it was. Throws
  /// std::runtime_error at once when another connection is writing.
  void beginBatch();
  void commitBatch();
  /// True when open() found a write that a killed writer left unfinished and rolled it back.
  bool recoveredJournal() const { return recovered_journal_; }

  /// Removes a place with its images and edges; false when there is no such place.
  bool removePlace(const std::string& place);
  /// Adds (or with connected = false removes) the undirected edge a - b; both places must exist.
  void setAdjacent(const std::string& a, const std::string& b, bool connected = true);

  std::vector<PlaceInfo> places() const;  // sorted by name
  /// Edges as pairs of names, each once, sorted.
  std::vector<std::pair<std::string, std::string>> edges() const;
  long imageCount() const;

  /// Loads the histograms of `spaces` (default: all stored) into a contiguous in-memory index,
  /// places in name order. Throws std::invalid_argument for a space the database lacks.
  PlaceIndex loadIndex(const std::vector<int>& spaces = {}) const;
  /// The whole-image descriptors of every image that has them, places in `index`'s order; empty
  /// when none are stored. Throws std::runtime_error naming both settings when they were made
  /// with settings other than `config`, or when a stored row is damaged.
  PlaceDescriptorIndex loadDescriptorIndex(const PlaceIndex& index,
                                           const GlobalDescriptorConfig& config) const;
  /// A reference traversal kept in the database (evaluate_places --reference A --database F):
  /// the whole-image descriptors of every image that has them, in the order stored, and in
  /// `sources` and `image_ids` (when given) each one's source and image id (TrainingFrame's).
  /// Empty when none are stored; throws as loadDescriptorIndex does.
  ReferenceTraversal loadTraversal(const GlobalDescriptorConfig& config,
                                   std::vector<std::string>* sources = nullptr,
                                   std::vector<long>* image_ids = nullptr) const;
  /// Every image that has SIFT features, in the order stored, with its place and pose.
  std::vector<TrainingFrame> loadFrames() const;
  /// Adjacency lists in the index's place order (for PlaceFilter).
  std::vector<std::vector<int>> adjacencyLists(const PlaceIndex& index) const;

 private:
  PlaceDatabase(sqlite3* db, std::string path, bool read_only);
  void exec(const std::string& sql) const;
  void readSettings();
  int placeId(const std::string& name, bool create);
  // Every stored image's whole-image descriptors in the order stored, with its place and source.
  void readDescriptors(
      const GlobalDescriptorConfig& config,
      const std::function<void(long long image_id, const std::string& place,
                               const std::string& source, const ImageDescriptors& d)>& visit) const;

  sqlite3* db_ = nullptr;
  std::string path_;
  bool read_only_ = false;
  bool in_batch_ = false;
  bool recovered_journal_ = false;
  DatabaseSettings settings_;
  std::string descriptor_settings_;
};

}  // namespace adaptive_perception::places
