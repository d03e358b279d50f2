#pragma once
// Image-to-room classification by SIFT matching (papers/002 section 4.1.1): the similarity of a
// test image to a training frame is the share of its features matched under Lowe's ratio test; the
// best n training frames vote for their rooms with their similarity, and a frame is classified only
// when the leading room holds more than 60% of the vote.
//
// Unlike the paper's loop over every training frame (0.18 s each, 3 minutes per image), all
// training descriptors sit in one FLANN kd-tree forest: each test descriptor's k nearest
// descriptors vote for their frames, and only the most voted candidate frames are verified by the
// exact per-frame ratio test.
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/flann.hpp>
#include <string>
#include <vector>

namespace adaptive_perception::places {

struct SiftConfig {
  int max_features = 200;            // strongest keypoints kept per image, 10..5000
  double contrast_threshold = 0.03;  // OpenCV SIFT contrastThreshold
  void validate() const;             // throws std::invalid_argument naming the bad field
};

/// SIFT descriptors of a bgr8 image: N x 128, CV_32F (values 0..255). Empty (0 x 128) when the
/// image has no keypoint.
cv::Mat extractSift(const cv::Mat& bgr8, const SiftConfig& config);

/// The paper's similarity: the share of `query` descriptors whose nearest descriptor in `frame` is
/// closer than `ratio` times the second nearest (Lowe's test), exact brute force. 0 when the query
/// is empty or the frame has fewer than two descriptors (no ratio to take).
double frameSimilarity(const cv::Mat& query, const cv::Mat& frame, double ratio = 0.8);

struct FrameMatch {
  int frame = -1;
  double similarity = 0.0;
};

struct FeatureIndexConfig {
  double ratio = 0.8;     // Lowe's ratio
  int knn = 8;            // nearest training descriptors looked up per test descriptor
  int candidates = 30;    // most voted frames verified exactly
  int trees = 4;          // FLANN kd-trees
  int checks = 64;        // FLANN leaves visited per query
  void validate() const;  // throws std::invalid_argument naming the bad field
};

class FeatureIndex {
 public:
  explicit FeatureIndex(FeatureIndexConfig config = {});
  /// Adds a training frame (frames are numbered in the order added); call build() after the last.
  int addFrame(const cv::Mat& descriptors);
  void build();
  int numFrames() const { return static_cast<int>(frames_.size()); }
  const cv::Mat& frameDescriptors(int frame) const { return frames_.at(frame); }

  /// The n most similar frames, most similar first, among the candidates the index proposes.
  /// Throws std::logic_error before build().
  std::vector<FrameMatch> topFrames(const cv::Mat& query, int n) const;
  /// Reference: every frame verified (the paper's loop).
  std::vector<FrameMatch> bruteForce(const cv::Mat& query, int n) const;

 private:
  FeatureIndexConfig config_;
  std::vector<cv::Mat> frames_;
  cv::Mat all_;             // every descriptor, stacked
  std::vector<int> owner_;  // frame of each row of all_
  std::unique_ptr<cv::flann::Index> index_;
  bool built_ = false;
};

/// The vote of the best frames (section 4.1.1, Tables 1-2): per room the sum of the frames'
/// similarities; classified as the leading room only when its sum exceeds `min_share` of the total.
struct RoomVote {
  int room = -1;  // -1: not classified
  double share = 0.0;
  std::vector<double> sums;  // per room
};
RoomVote voteRooms(const std::vector<FrameMatch>& best, const std::vector<int>& frame_room,
                   int num_rooms, double min_share = 0.6);

/// ImageCLEF 2009 RobotVision scoring: +1 per correct room, -0.5 per wrong one, 0 when not
/// classified.
struct ClefScore {
  long correct = 0, misclassified = 0, not_classified = 0;
  void add(int predicted, int truth) {
    if (predicted < 0)
      ++not_classified;
    else if (predicted == truth)
      ++correct;
    else
      ++misclassified;
  }
  double score() const { return correct - 0.5 * misclassified; }
};

}  // namespace adaptive_perception::places
