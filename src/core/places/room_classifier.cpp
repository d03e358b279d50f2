#include "adaptive_perception/places/room_classifier.h"

#include <algorithm>
#include <stdexcept>

namespace adaptive_perception::places {

const config::Fields<RoomClassifierConfig>& RoomClassifierConfig::fields() {
  using C = RoomClassifierConfig;
  using config::closed;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("best_frames", &C::best_frames, closed(1, 1000), "training frames that vote")
          .add("min_share", &C::min_share, config::Range{0, 1, false, true},
               "the leading room needs more than this share of the vote")
          .add("max_features", &C::sift, &SiftConfig::max_features, closed(10, 5000),
               "SIFT keypoints per image")
          .add("candidates", &C::index, &FeatureIndexConfig::candidates, closed(1, 10000),
               "frames the indexed matcher verifies exactly")
          .add("structure_weight", &C::structure, &StructureVoteConfig::weight, closed(0, 1),
               "weight of line-structure similarity (papers/002 4.1.2) against SIFT; 0: off")
          .add("structure_floor", &C::structure, &StructureVoteConfig::floor,
               config::Range{0, 1, false, true},
               "structural similarity that counts as none (restrictive detection)");
  return f;
}

void RoomClassifierConfig::validate() const {
  fields().validate(*this);
  sift.validate();
  index.validate();
  lines.validate();
  structure.validate();
}

RoomClassifier::RoomClassifier(RoomClassifierConfig config)
    : config_(config), index_(config.index) {
  config_.validate();
}

void RoomClassifier::setFrames(std::vector<TrainingFrame> frames) {
  if (frames.empty())
    throw std::invalid_argument("no training frame with SIFT features (train_places --features)");
  frames_ = std::move(frames);
  rooms_.clear();
  for (const TrainingFrame& f : frames_) rooms_.push_back(f.place);
  std::sort(rooms_.begin(), rooms_.end());
  rooms_.erase(std::unique(rooms_.begin(), rooms_.end()), rooms_.end());
  index_ = FeatureIndex(config_.index);
  frame_room_.clear();
  for (const TrainingFrame& f : frames_) {
    index_.addFrame(f.features);
    frame_room_.push_back(roomIndex(f.place));
  }
  index_.build();
  structure_.release();
  if (config_.structure.enabled()) {
    const int dims = config_.lines.dims();
    structure_.create(static_cast<int>(frames_.size()), dims, CV_32F);
    for (size_t i = 0; i < frames_.size(); ++i) {
      const cv::Mat& st = frames_[i].structure;
      if (st.empty())
        throw std::invalid_argument(
            "structural cues are on but training image " + std::to_string(frames_[i].image_id) +
            " has no line-structure descriptor (retrain with train_places --features)");
      if (static_cast<int>(st.total()) != dims)
        throw std::invalid_argument("training image " + std::to_string(frames_[i].image_id) +
                                    " has a line-structure descriptor of " +
                                    std::to_string(st.total()) + " values, the configuration " +
                                    std::to_string(dims) + " (orientation_bins x bands)");
      st.reshape(1, 1).copyTo(structure_.row(static_cast<int>(i)));
    }
  }
}

int RoomClassifier::roomIndex(const std::string& name) const {
  const auto it = std::lower_bound(rooms_.begin(), rooms_.end(), name);
  return it != rooms_.end() && *it == name ? static_cast<int>(it - rooms_.begin()) : -1;
}

ImageCues RoomClassifier::extract(const cv::Mat& bgr8) const {
  ImageCues cues;
  cues.sift = extractSift(bgr8, config_.sift);
  if (config_.structure.enabled()) cues.structure = lineStructure(bgr8, config_.lines);
  return cues;
}

std::vector<FrameMatch> RoomClassifier::frameSimilarities(const ImageCues& cues, int n) const {
  if (!config_.structure.enabled()) return index_.topFrames(cues.sift, n);
  if (static_cast<int>(cues.structure.total()) != config_.lines.dims())
    throw std::invalid_argument("frameSimilarities: the image has no line-structure descriptor");
  // The SIFT list is the index's verified candidates; the structural list covers every frame.
  const std::vector<FrameMatch> sift =
      index_.topFrames(cues.sift, std::max(n, config_.index.candidates));
  std::vector<double> st(frames_.size());
  for (int i = 0; i < structure_.rows; ++i)
    st[i] = structureSimilarity(structure_.row(i), cues.structure.reshape(1, 1));
  return combineStructure(sift, st, config_.structure, n);
}

RoomClassification RoomClassifier::classify(const cv::Mat& bgr8) const {
  return classifyCues(extract(bgr8));
}

RoomClassification RoomClassifier::classifyDescriptors(const cv::Mat& descriptors) const {
  if (config_.structure.enabled())
    throw std::logic_error("classifyDescriptors: structural cues are on; use classifyCues");
  return classifyCues({descriptors, cv::Mat()});
}

RoomClassification RoomClassifier::classifyCues(const ImageCues& cues) const {
  RoomClassification out;
  out.features = cues.sift.rows;
  out.best = frameSimilarities(cues, config_.best_frames);
  const RoomVote v =
      voteRooms(out.best, frame_room_, static_cast<int>(rooms_.size()), config_.min_share);
  out.room = v.room;
  out.share = v.share;
  out.sums = v.sums;
  return out;
}

}  // namespace adaptive_perception::places
