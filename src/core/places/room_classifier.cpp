#include "adaptive_perception/places/room_classifier.h"

#include <algorithm>
#include <stdexcept>

namespace adaptive_perception::places {

void RoomClassifierConfig::validate() const {
  sift.validate();
  index.validate();
  if (best_frames < 1 || best_frames > 1000)
    throw std::invalid_argument("best_frames must be in 1..1000");
  if (!(min_share >= 0.0 && min_share < 1.0))
    throw std::invalid_argument("min_share must be in [0, 1)");
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
}

int RoomClassifier::roomIndex(const std::string& name) const {
  const auto it = std::lower_bound(rooms_.begin(), rooms_.end(), name);
  return it != rooms_.end() && *it == name ? static_cast<int>(it - rooms_.begin()) : -1;
}

RoomClassification RoomClassifier::classify(const cv::Mat& bgr8) const {
  return classifyDescriptors(extractSift(bgr8, config_.sift));
}

RoomClassification RoomClassifier::classifyDescriptors(const cv::Mat& descriptors) const {
  RoomClassification out;
  out.features = descriptors.rows;
  out.best = index_.topFrames(descriptors, config_.best_frames);
  const RoomVote v =
      voteRooms(out.best, frame_room_, static_cast<int>(rooms_.size()), config_.min_share);
  out.room = v.room;
  out.share = v.share;
  out.sums = v.sums;
  return out;
}

}  // namespace adaptive_perception::places
