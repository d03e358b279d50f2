#include "adaptive_perception/places/place_matcher.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace adaptive_perception::places {

int PlaceIndex::addPlace(const std::string& name) {
  const int existing = placeIndex(name);
  if (existing >= 0) return existing;
  names_.push_back(name);
  for (auto& c : counts_) c.push_back(0);
  return numPlaces() - 1;
}

int PlaceIndex::placeIndex(const std::string& name) const {
  const auto it = std::find(names_.begin(), names_.end(), name);
  return it == names_.end() ? -1 : static_cast<int>(it - names_.begin());
}

void PlaceIndex::addImage(int place, const ImageHistograms& h) {
  if (place < 0 || place >= numPlaces())
    throw std::invalid_argument("PlaceIndex::addImage: unknown place index " +
                                std::to_string(place));
  if (h.bins != bins_)
    throw std::invalid_argument("PlaceIndex::addImage: histograms have " + std::to_string(h.bins) +
                                " bins, the index " + std::to_string(bins_));
  for (int s = 0; s < kNumSpaces; ++s) {
    if (!h.has(s)) continue;
    if (static_cast<int>(h.spaces[s].size()) != 3 * bins_)
      throw std::invalid_argument("PlaceIndex::addImage: histogram of " + spaceName(s) +
                                  " has the wrong length");
    rows_[s].data.insert(rows_[s].data.end(), h.spaces[s].begin(), h.spaces[s].end());
    rows_[s].k_terms.push_back(HistogramQuery::storedTerms(h.spaces[s].data(), bins_));
    rows_[s].place.push_back(place);
    ++counts_[s][place];
  }
}

int PlaceIndex::imageCount(int place, int space) const { return counts_[space].at(place); }

std::vector<double> PlaceIndex::nodeDistances(int space, Distance d,
                                              const ImageHistograms& test) const {
  if (space < 0 || space >= kNumSpaces || !test.has(space))
    throw std::invalid_argument("nodeDistances: the test image has no histogram in space " +
                                std::to_string(space));
  if (test.bins != bins_)
    throw std::invalid_argument("nodeDistances: test histograms have " + std::to_string(test.bins) +
                                " bins, the index " + std::to_string(bins_));
  std::vector<double> sum(names_.size(), 0.0);
  const Rows& rows = rows_[space];
  const int len = 3 * bins_;
  const HistogramQuery query(d, test.spaces[space].data(), bins_);
  for (size_t r = 0; r < rows.place.size(); ++r)
    sum[rows.place[r]] += query(rows.data.data() + r * len, rows.k_terms[r]);
  std::vector<double> out(names_.size(), std::numeric_limits<double>::infinity());
  for (size_t p = 0; p < names_.size(); ++p)
    if (counts_[space][p] > 0) out[p] = sum[p] / counts_[space][p];
  return out;
}

Recognition combineTestImages(const std::vector<std::vector<double>>& node_distances, int space,
                              Distance method) {
  if (node_distances.empty()) throw std::invalid_argument("combineTestImages: no test image");
  const size_t n = node_distances.front().size();
  if (n == 0) throw std::invalid_argument("combineTestImages: no place");
  Recognition r;
  r.space = space;
  r.method = method;
  r.test_images = static_cast<int>(node_distances.size());
  r.total_distances.assign(n, 0.0);
  r.votes.assign(n, 0);
  for (const auto& d : node_distances) {
    if (d.size() != n) throw std::invalid_argument("combineTestImages: rows of different lengths");
    for (size_t x = 0; x < n; ++x) r.total_distances[x] += d[x] / r.test_images;  // eq. (6)
    ++r.votes[std::min_element(d.begin(), d.end()) - d.begin()];
  }
  r.place = static_cast<int>(std::min_element(r.total_distances.begin(), r.total_distances.end()) -
                             r.total_distances.begin());
  r.confidence = static_cast<double>(r.votes[r.place]) / r.test_images;  // eq. (7)
  double second = std::numeric_limits<double>::infinity();
  for (size_t x = 0; x < n; ++x)
    if (static_cast<int>(x) != r.place) second = std::min(second, r.total_distances[x]);
  const double best = r.total_distances[r.place];
  r.margin = std::isfinite(second) && second > 0.0 ? (second - best) / second
             : std::isfinite(second)               ? 0.0
                                                   : 1.0;
  return r;
}

std::vector<Recognition> recognizeAll(const PlaceIndex& index,
                                      const std::vector<ImageHistograms>& test_images,
                                      const std::vector<int>& spaces,
                                      const std::vector<Distance>& methods) {
  std::vector<Recognition> out;
  for (int s : spaces) {
    if (!index.hasSpace(s)) continue;
    for (Distance m : methods) {
      std::vector<std::vector<double>> per_image;
      per_image.reserve(test_images.size());
      for (const ImageHistograms& t : test_images)
        per_image.push_back(index.nodeDistances(s, m, t));
      out.push_back(combineTestImages(per_image, s, m));
    }
  }
  return out;
}

const Recognition& mostConfident(const std::vector<Recognition>& candidates) {
  if (candidates.empty()) throw std::invalid_argument("mostConfident: no candidate");
  const Recognition* best = &candidates.front();
  for (const Recognition& r : candidates)
    if (r.confidence > best->confidence ||
        (r.confidence == best->confidence && r.margin > best->margin))
      best = &r;
  return *best;
}

}  // namespace adaptive_perception::places
