#include "adaptive_perception/places/place_recognizer.h"

#include <algorithm>
#include <stdexcept>

namespace adaptive_perception::places {

const config::Fields<PlaceRecognizerConfig>& PlaceRecognizerConfig::fields() {
  using C = PlaceRecognizerConfig;
  using config::closed;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("thumbnail_weight", &C::fusion, &FusionWeights::thumbnail, closed(0, 1000),
               "the fused cue's weight of the thumbnail (the weights: not all 0)")
          .add("gradient_weight", &C::fusion, &FusionWeights::gradient, closed(0, 1000),
               "... of the gradient descriptor")
          .add("chromaticity_weight", &C::fusion, &FusionWeights::chromaticity, closed(0, 1000),
               "... of the chromaticity histogram")
          .add("layout_weight", &C::fusion, &FusionWeights::layout, closed(0, 1000),
               "... of the layout (equalised grey levels by region)")
          .add("window", &C::window, closed(1, 1000), "images combined by eqs. 6-7 (sliding)")
          .add("use_filter", &C::use_filter, "the topological Bayes filter over the adjacency")
          .add("stay_probability", &C::filter, &PlaceFilterConfig::stay_probability,
               closed(0, 1), "filter: chance to stay in a place between images")
          .add("teleport_probability", &C::filter, &PlaceFilterConfig::teleport_probability,
               closed(0, 1), "filter: chance to jump anywhere (at most 1 - stay_probability)")
          .add("likelihood_sharpness", &C::filter, &PlaceFilterConfig::likelihood_sharpness,
               closed(1e-3, 1e3), "filter: k of exp(-k (D - Dmin) / (Dmedian - Dmin))")
          .add("use_sequence", &C::use_sequence,
               "filter, whole-image cues: also observe the sequence matcher (for a database "
               "that is one continuous drive)")
          .add("sequence_frames", &C::sequence, &SequenceMatcherConfig::sequence_frames,
               closed(1, 1000), "sequence matcher: images on one trajectory")
          .add("use_route", &C::use_route,
               "filter, whole-image cues, a database that is one drive (each place one image, "
               "joined in the order stored): the route filter over its images answers")
          .add("route_likelihood_gain", &C::route, &RouteFilterConfig::likelihood_gain,
               config::aboveZero(100), "route filter: likelihood exp(-gain * distance z-score)")
          .add("route_jump_probability", &C::route, &RouteFilterConfig::jump_probability,
               config::belowOne(), "route filter: chance per image of a jump anywhere (kidnap)")
          .add("route_stop_probability", &C::route, &RouteFilterConfig::stop_probability,
               closed(0, 1), "route filter: chance per image that a moving robot stands still")
          .add("route_start_probability", &C::route, &RouteFilterConfig::start_probability,
               closed(0, 1), "route filter: chance per image that a still robot drives off");
  return f;
}

void PlaceRecognizerConfig::validate() const {
  fields().validate(*this);
  if (cue != "histogram" && !isCueName(cue))
    throw std::invalid_argument("cue '" + cue +
                                "' is not one of fused, thumbnail, gradient, chromaticity, "
                                "histogram");
  fusion.validate();
  if (color_space != "auto") spaceIndex(color_space);  // throws naming the valid ones
  if (method != "auto") distanceFromName(method);
  filter.validate();
  sequence.validate();
  route.validate();
}

PlaceRecognizer::PlaceRecognizer(PlaceRecognizerConfig config) : config_(std::move(config)) {
  config_.validate();
  methods_ = config_.method == "auto" ? parseDistances("paper")
                                      : std::vector<Distance>{distanceFromName(config_.method)};
}

void PlaceRecognizer::setDatabase(PlaceIndex index, std::vector<std::vector<int>> adjacency,
                                  PlaceDescriptorIndex descriptors) {
  if (static_cast<int>(adjacency.size()) != index.numPlaces())
    throw std::invalid_argument("setDatabase: adjacency for " + std::to_string(adjacency.size()) +
                                " places, the index has " + std::to_string(index.numPlaces()));
  if (usesDescriptors()) {
    int stored = 0;
    for (int s = 0; s < kNumSpaces; ++s) stored = std::max(stored, index.totalImages(s));
    if (descriptors.numPlaces() != index.numPlaces() || descriptors.totalImages() < stored)
      throw std::invalid_argument(
          "the place database holds " + std::to_string(stored) + " training images but " +
          std::to_string(descriptors.totalImages()) +
          " with whole-image descriptors (stored "
          "before the cues existed?): train it again, or set the cue to histogram");
  }
  descriptors_ = std::move(descriptors);
  std::vector<int> spaces;
  if (config_.color_space == "auto") {
    for (int s = 0; s < kNumSpaces; ++s)
      if (index.hasSpace(s)) spaces.push_back(s);
  } else {
    const int s = spaceIndex(config_.color_space);
    if (index.numPlaces() > 0 && !index.hasSpace(s))
      throw std::invalid_argument("the place database has no " + config_.color_space +
                                  " histograms");
    spaces.push_back(s);
  }
  index_ = std::move(index);
  spaces_ = spaces;
  adjacency_ = std::move(adjacency);
  reset();
}

void PlaceRecognizer::reset() {
  window_.clear();
  seen_ = 0;
  filter_.clear();
  sequence_.clear();
  route_.clear();
  if (config_.use_filter && index_.numPlaces() > 0) {
    filter_.emplace_back(adjacency_, config_.filter);
    if (config_.use_sequence && usesDescriptors() && descriptors_.totalImages() > 0)
      sequence_.emplace_back(config_.sequence);
    if (config_.use_route && usesDescriptors() && isOneDrive()) route_.emplace_back(config_.route);
  }
}

bool PlaceRecognizer::isOneDrive() const {
  const int n = descriptors_.totalImages();
  if (n < 2 || n != descriptors_.numPlaces()) return false;
  for (int r = 1; r < n; ++r) {
    const int a = descriptors_.placeOfImage(r - 1), b = descriptors_.placeOfImage(r);
    const auto& next = adjacency_.at(static_cast<size_t>(a));
    if (std::find(next.begin(), next.end(), b) == next.end()) return false;
  }
  return true;
}

PlaceResult PlaceRecognizer::add(const ImageHistograms& h, const ImageDescriptors* d) {
  if (index_.numPlaces() == 0 || spaces_.empty())
    throw std::logic_error("the place database has no trained place yet");
  std::vector<std::vector<double>> per_combo;
  std::vector<double> sequence_nodes;
  if (usesDescriptors()) {
    if (!d)
      throw std::invalid_argument("PlaceRecognizer::add: the " + config_.cue +
                                  " cue needs the image's whole-image descriptors");
    const std::vector<float> images =
        descriptors_.imageDistances(cueWeights(config_.cue, config_.fusion), *d);
    per_combo.push_back(descriptors_.nodeDistancesOf(images));
    if (!sequence_.empty()) sequence_nodes = descriptors_.nodeDistancesOf(sequence_[0].add(images));
    if (!route_.empty()) route_[0].add(images);
  } else {
    for (int s : spaces_)
      for (Distance m : methods_) per_combo.push_back(index_.nodeDistances(s, m, h));
  }
  window_.push_back(std::move(per_combo));
  while (static_cast<int>(window_.size()) > config_.window) window_.pop_front();

  std::vector<Recognition> recs;
  size_t c = 0;
  const auto combine = [&](int s, Distance m) {
    std::vector<std::vector<double>> rows;
    for (const auto& img : window_) rows.push_back(img[c]);
    recs.push_back(combineTestImages(rows, s, m));
    ++c;
  };
  if (usesDescriptors()) {
    combine(-1, Distance::kChiSquare);  // no colour space, no histogram distance
  } else {
    for (int s : spaces_)
      for (Distance m : methods_) combine(s, m);
  }
  ++seen_;
  PlaceResult out;
  out.cue = config_.cue;
  const Recognition& best = mostConfident(recs);
  out.recognition = best;
  out.images = static_cast<int>(window_.size());
  if (!filter_.empty()) {
    const size_t chosen = &best - recs.data();
    if (seen_ > 0) filter_[0].predict();
    filter_[0].update(window_.back()[chosen]);
    if (!sequence_nodes.empty()) {
      filter_[0].update(sequence_nodes);
      out.sequence_place = static_cast<int>(
          std::min_element(sequence_nodes.begin(), sequence_nodes.end()) - sequence_nodes.begin());
    }
    out.belief = filter_[0].belief();
    out.filtered_place = filter_[0].best();
    out.filtered_confidence = out.belief[out.filtered_place];
    if (!route_.empty()) {  // the route filter's posterior, summed per place, answers
      const RouteFilter& route = route_[0];
      std::fill(out.belief.begin(), out.belief.end(), 0.0);
      for (int r = 0; r < static_cast<int>(route.posterior().size()); ++r)
        out.belief[descriptors_.placeOfImage(r)] += route.posterior()[r];
      out.route_frame = route.best();
      out.filtered_place = descriptors_.placeOfImage(route.best());
      out.filtered_confidence = route.confidence();
    }
  }
  return out;
}

}  // namespace adaptive_perception::places
