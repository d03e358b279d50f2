#pragma once
// Image-to-room classification (papers/002 section 4.1.1, the obligatory track): SIFT features of
// the image, the best n training frames from the indexed matcher (feature_index.h), and their vote
// with the 60% rule. Optionally (structure.weight > 0) the frames' line-structure similarity
// (line_structure.h, section 4.1.2) joins the SIFT similarity before the vote. Training frames come
// from the place database (PlaceDatabase::loadFrames).
#include <string>
#include <vector>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/places/feature_index.h"
#include "adaptive_perception/places/line_structure.h"
#include "adaptive_perception/places/place_database.h"

namespace adaptive_perception::places {

struct RoomClassifierConfig {
  SiftConfig sift;
  FeatureIndexConfig index;
  int best_frames = 20;           // n: training frames that vote, 1..1000
  double min_share = 0.6;         // the leading room needs more than this share of the vote, [0, 1)
  LineStructureConfig lines;      // the structural descriptor (must match the training's)
  StructureVoteConfig structure;  // its vote; weight 0 (the default) leaves it out
  /// The fields appearance_localizer sets (config/fields.h): best_frames, min_share,
  /// max_features, candidates, structure_weight, structure_floor.
  static const config::Fields<RoomClassifierConfig>& fields();
  void validate() const;          // throws std::invalid_argument naming the bad field
};

/// What an image is compared by: SIFT descriptors, and its line structure when that is used.
struct ImageCues {
  cv::Mat sift;       // N x 128 CV_32F
  cv::Mat structure;  // 1 x D CV_32F; empty when structural cues are off
};

struct RoomClassification {
  int room = -1;  // index into rooms(); -1 = not classified
  double share = 0.0;
  std::vector<double> sums;      // per room
  std::vector<FrameMatch> best;  // the voting frames
  int features = 0;              // in the test image
};

class RoomClassifier {
 public:
  explicit RoomClassifier(RoomClassifierConfig config = {});
  /// Installs the training frames (rooms are their places, in name order) and builds the index.
  /// Throws std::invalid_argument when there is no frame, or when structural cues are on and a
  /// frame lacks a line-structure descriptor of the configured size.
  void setFrames(std::vector<TrainingFrame> frames);
  const std::vector<std::string>& rooms() const { return rooms_; }
  int roomIndex(const std::string& name) const;  // -1 when unknown
  const std::vector<TrainingFrame>& frames() const { return frames_; }
  const std::vector<int>& frameRooms() const { return frame_room_; }

  RoomClassification classify(const cv::Mat& bgr8) const;
  RoomClassification classifyDescriptors(const cv::Mat& descriptors) const;  // SIFT only
  RoomClassification classifyCues(const ImageCues& cues) const;

  /// The cues of a bgr8 image under this configuration.
  ImageCues extract(const cv::Mat& bgr8) const;
  /// Up to `n` frames most similar to the image, most similar first: the indexed SIFT matcher's
  /// verified frames, joined with the structural similarity when it is on (combineStructure).
  std::vector<FrameMatch> frameSimilarities(const ImageCues& cues, int n) const;
  const RoomClassifierConfig& config() const { return config_; }
  const FeatureIndex& index() const { return index_; }

 private:
  RoomClassifierConfig config_;
  std::vector<TrainingFrame> frames_;
  std::vector<std::string> rooms_;
  std::vector<int> frame_room_;
  FeatureIndex index_;
  cv::Mat structure_;  // frames x D, when structural cues are on
};

}  // namespace adaptive_perception::places
