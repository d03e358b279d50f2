// The place database's readers: places, edges, the in-memory indexes and the stored frames
// (place_database.h). The writers and the schema are in place_database.cpp.
#include <sqlite3.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>

#include "adaptive_perception/places/place_database.h"
#include "sqlite_statement.h"

namespace adaptive_perception::places {

using sqlite_detail::Statement;

namespace {
// Steps through the rows of `q`, which are ordered by the image id in column 1 (the id is never
// negative): `start(id)` at an image's first row, `row(id)` at each of its rows, `finish(id)`
// after its last.
template <class Start, class Row, class Finish>
void forEachImage(Statement& q, Start&& start, Row&& row, Finish&& finish) {
  long long current = -1;
  while (q.step()) {
    const long long id = q.integer(1);
    if (id != current) {
      if (current >= 0) finish(current);
      current = id;
      start(id);
    }
    row(id);
  }
  if (current >= 0) finish(current);
}

// A stored blob of floats whose values a reader cannot use: "value K is nan" (or inf, or negative
// where `non_negative`) for the first such value, empty when every value holds. A NaN or negative
// histogram bin would make every distance to that image NaN, and the best place an arbitrary one.
std::string badFloats(const void* data, int count, bool non_negative) {
  for (int k = 0; k < count; ++k) {
    float v;
    std::memcpy(&v, static_cast<const char*>(data) + k * sizeof(float), sizeof(float));
    if (!std::isfinite(v) || (non_negative && v < 0.0f))
      return "value " + std::to_string(k) + " is " +
             (std::isnan(v) ? std::string("nan") : std::isinf(v) ? "infinite" : std::to_string(v));
  }
  return "";
}
}  // namespace

std::vector<PlaceInfo> PlaceDatabase::places() const {
  Statement q(db_,
              "SELECT p.name, COUNT(i.id) FROM places p LEFT JOIN images i ON i.place_id = p.id "
              "GROUP BY p.id ORDER BY p.name",
              path_);
  std::vector<PlaceInfo> out;
  while (q.step()) out.push_back({q.text(0), static_cast<int>(q.integer(1))});
  return out;
}

std::vector<std::pair<std::string, std::string>> PlaceDatabase::edges() const {
  Statement q(db_,
              "SELECT pa.name, pb.name FROM adjacency j JOIN places pa ON pa.id = j.a JOIN "
              "places pb ON pb.id = j.b",
              path_);
  std::vector<std::pair<std::string, std::string>> out;
  while (q.step()) {
    std::string a = q.text(0), b = q.text(1);
    if (b < a) std::swap(a, b);
    out.emplace_back(a, b);
  }
  std::sort(out.begin(), out.end());
  return out;
}

long PlaceDatabase::imageCount() const {
  Statement q(db_, "SELECT COUNT(*) FROM images", path_);
  q.step();
  return static_cast<long>(q.integer(0));
}

PlaceIndex PlaceDatabase::loadIndex(const std::vector<int>& spaces_in) const {
  const std::vector<int> spaces = spaces_in.empty() ? settings_.spaces : spaces_in;
  std::vector<bool> wanted(kNumSpaces, false);
  for (int s : spaces) {
    if (std::find(settings_.spaces.begin(), settings_.spaces.end(), s) == settings_.spaces.end())
      throw std::invalid_argument(path_ + ": the database has no " + spaceName(s) +
                                  " histograms (it has " + spacesToString(settings_.spaces) + ")");
    wanted[s] = true;
  }
  PlaceIndex index(settings_.bins);
  for (const PlaceInfo& p : places()) index.addPlace(p.name);
  Statement q(db_,
              "SELECT p.name, h.image_id, h.space, h.data FROM histograms h JOIN images i ON "
              "i.id = h.image_id JOIN places p ON p.id = i.place_id ORDER BY h.image_id, h.space",
              path_);
  const int bytes = 3 * settings_.bins * static_cast<int>(sizeof(float));
  std::string place;
  ImageHistograms h;
  forEachImage(
      q,
      [&](long long) {
        place = q.text(0);
        h = ImageHistograms();
        h.bins = settings_.bins;
      },
      [&](long long id) {
        const int s = static_cast<int>(q.integer(2));
        if (s < 0 || s >= kNumSpaces || !wanted[s]) return;
        if (q.bytes(3) != bytes)
          throw std::runtime_error(path_ + ": image " + std::to_string(id) + " has a " +
                                   std::to_string(q.bytes(3)) + "-byte histogram, expected " +
                                   std::to_string(bytes));
        const std::string bad = badFloats(q.blob(3), 3 * settings_.bins, true);
        if (!bad.empty())
          throw std::runtime_error(path_ + ": image " + std::to_string(id) + " has a damaged " +
                                   spaceName(s) + " histogram (" + bad + ")");
        h.spaces[s].resize(3 * settings_.bins);
        std::memcpy(h.spaces[s].data(), q.blob(3), bytes);
      },
      [&](long long) { index.addImage(index.placeIndex(place), h); });
  return index;
}

void PlaceDatabase::readDescriptors(
    const GlobalDescriptorConfig& config,
    const std::function<void(long long image_id, const std::string& place,
                             const std::string& source, const ImageDescriptors& d)>& visit) const {
  if (descriptor_settings_.empty()) return;
  if (descriptor_settings_ != config.toString())
    throw std::runtime_error(path_ + ": its whole-image descriptors were made with " +
                             descriptor_settings_ + ", asked for " + config.toString() +
                             "; use those settings or build a new database");
  Statement q(db_,
              "SELECT p.name, d.image_id, d.kind, d.data, i.source FROM descriptors d JOIN images "
              "i ON i.id = d.image_id JOIN places p ON p.id = i.place_id ORDER BY d.image_id, "
              "d.kind",
              path_);
  std::string place, source;
  ImageDescriptors d;
  forEachImage(
      q,
      [&](long long) {
        place = q.text(0);
        source = q.text(4);
        d.rows.clear();
      },
      [&](long long id) {
        const int kind = static_cast<int>(q.integer(2));
        const int expected = kind >= 0 && kind < kNumDescriptorKinds
                                 ? config.length(static_cast<DescriptorKind>(kind))
                                 : -1;
        if (kind != static_cast<int>(d.rows.size()) || q.bytes(3) != expected)
          throw std::runtime_error(path_ + ": image " + std::to_string(id) +
                                   " has a damaged whole-image descriptor (kind " +
                                   std::to_string(kind) + ", " + std::to_string(q.bytes(3)) +
                                   " bytes)");
        cv::Mat row(1, expected, CV_8UC1);
        std::memcpy(row.data, q.blob(3), expected);
        d.rows.push_back(row);
      },
      [&](long long id) {
        if (d.rows.size() != static_cast<size_t>(kNumDescriptorKinds))
          throw std::runtime_error(path_ + ": image " + std::to_string(id) +
                                   " lacks some of its whole-image descriptors");
        visit(id, place, source, d);
      });
}

PlaceDescriptorIndex PlaceDatabase::loadDescriptorIndex(
    const PlaceIndex& index, const GlobalDescriptorConfig& config) const {
  PlaceDescriptorIndex out(index.placeNames(), config);
  readDescriptors(config,
                  [&](long long, const std::string& place, const std::string&,
                      const ImageDescriptors& d) { out.addImage(index.placeIndex(place), d); });
  return out;
}

ReferenceTraversal PlaceDatabase::loadTraversal(const GlobalDescriptorConfig& config,
                                                std::vector<std::string>* sources,
                                                std::vector<long>* image_ids) const {
  ReferenceTraversal out(config);
  if (sources) sources->clear();
  if (image_ids) image_ids->clear();
  readDescriptors(config, [&](long long id, const std::string&, const std::string& source,
                              const ImageDescriptors& d) {
    out.add(d);
    if (sources) sources->push_back(source);
    if (image_ids) image_ids->push_back(static_cast<long>(id));
  });
  return out;
}

std::vector<TrainingFrame> PlaceDatabase::loadFrames() const {
  std::vector<TrainingFrame> out;
  const auto has_table = [&](const char* name) {
    Statement q(db_, "SELECT COUNT(*) FROM sqlite_master WHERE type = 'table' AND name = ?", path_);
    q.bind(1, std::string(name));
    q.step();
    return q.integer(0) > 0;
  };
  if (!has_table("features")) return out;  // an older file opened read-only: no features
  const bool structure = has_table("structure");
  Statement q(db_,
              std::string("SELECT i.id, p.name, f.rows, f.data, o.x_m, o.y_m, o.yaw_rad, ") +
                  (structure ? "s.data" : "NULL") +
                  " FROM features f JOIN images i ON i.id = f.image_id JOIN places p ON p.id = "
                  "i.place_id LEFT JOIN poses o ON o.image_id = i.id " +
                  (structure ? "LEFT JOIN structure s ON s.image_id = i.id " : "") +
                  "ORDER BY i.id",
              path_);
  while (q.step()) {
    TrainingFrame f;
    f.image_id = q.integer(0);
    f.place = q.text(1);
    const long long rows = q.integer(2);
    if (rows < 0 || q.bytes(3) != rows * 128)
      throw std::runtime_error(path_ + ": image " + std::to_string(f.image_id) +
                               " has a damaged feature blob");
    if (rows > 0) {
      const cv::Mat bytes(static_cast<int>(rows), 128, CV_8U, const_cast<void*>(q.blob(3)));
      bytes.convertTo(f.features, CV_32F);
    } else {
      f.features = cv::Mat(0, 128, CV_32F);
    }
    f.has_pose = !q.isNull(4);
    if (f.has_pose) {
      f.x_m = q.real(4);
      f.y_m = q.real(5);
      f.yaw_rad = q.real(6);
      if (!std::isfinite(f.x_m) || !std::isfinite(f.y_m) || !std::isfinite(f.yaw_rad))
        throw std::runtime_error(path_ + ": image " + std::to_string(f.image_id) +
                                 " has a pose that is not finite");
    }
    if (!q.isNull(7)) {
      const int bytes = q.bytes(7);
      if (bytes <= 0 || bytes % static_cast<int>(sizeof(float)) != 0)
        throw std::runtime_error(path_ + ": image " + std::to_string(f.image_id) +
                                 " has a damaged line-structure blob");
      const std::string bad = badFloats(q.blob(7), bytes / static_cast<int>(sizeof(float)), false);
      if (!bad.empty())
        throw std::runtime_error(path_ + ": image " + std::to_string(f.image_id) +
                                 " has a damaged line-structure blob (" + bad + ")");
      f.structure.create(1, bytes / static_cast<int>(sizeof(float)), CV_32F);
      std::memcpy(f.structure.data, q.blob(7), bytes);
    }
    out.push_back(std::move(f));
  }
  return out;
}

std::vector<std::vector<int>> PlaceDatabase::adjacencyLists(const PlaceIndex& index) const {
  std::vector<std::vector<int>> adj(index.numPlaces());
  for (const auto& [a, b] : edges()) {
    const int ia = index.placeIndex(a), ib = index.placeIndex(b);
    if (ia < 0 || ib < 0) continue;
    adj[ia].push_back(ib);
    adj[ib].push_back(ia);
  }
  return adj;
}

}  // namespace adaptive_perception::places
