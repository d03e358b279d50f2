// Structural cues (papers/002 section 4.1.2): the line-structure descriptor of known segments by
// hand, Hough detection on drawn images (and under darker lighting), the similarity, the weighted
// join with the SIFT similarity, and the room classifier's use of stored descriptors.
#include "adaptive_perception/places/line_structure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "adaptive_perception/places/room_classifier.h"

using namespace adaptive_perception::places;

namespace {
float at(const cv::Mat& d, int band, int bin, const LineStructureConfig& c) {
  return d.at<float>(0, band * c.orientation_bins + bin);
}
// A corridor-like picture: strong horizontal and vertical edges of rectangles.
cv::Mat boxes(double gain) {
  cv::Mat img(240, 320, CV_8UC3, cv::Scalar(60, 60, 60) * gain);
  cv::rectangle(img, cv::Rect(20, 30, 120, 80), cv::Scalar(200, 200, 200) * gain, cv::FILLED);
  cv::rectangle(img, cv::Rect(180, 120, 110, 100), cv::Scalar(160, 180, 200) * gain, cv::FILLED);
  return img;
}
}  // namespace

TEST(LineStructure, DescriptorOfKnownSegmentsByHand) {
  LineStructureConfig c;         // 12 orientation bins of 15 degrees, 3 bands
  const cv::Size size(100, 60);  // width + height = 160; bands of 20 rows
  const std::vector<cv::Vec4i> segs = {
      {0, 10, 80, 10},   // horizontal, 80 px, band 0, bin 0
      {50, 0, 50, 59},   // vertical, 59 px, midpoint row 29.5: band 1, bin 6 (90 degrees)
      {0, 59, 59, 0},    // rising diagonal: -45 degrees = 135 degrees, bin 9, band 1
      {10, 50, 40, 50},  // horizontal, 30 px, band 2
      {5, 5, 5, 5}};     // a point: no length, ignored
  const cv::Mat d = lineStructureOf(segs, size, c);
  ASSERT_EQ(d.cols, 36);
  EXPECT_FLOAT_EQ(at(d, 0, 0, c), 80.0f / 160.0f);
  EXPECT_FLOAT_EQ(at(d, 1, 6, c), 59.0f / 160.0f);
  EXPECT_FLOAT_EQ(at(d, 1, 9, c), static_cast<float>(59.0 * std::sqrt(2.0) / 160.0));
  EXPECT_FLOAT_EQ(at(d, 2, 0, c), 30.0f / 160.0f);
  EXPECT_NEAR(cv::sum(d)[0], (80.0 + 59.0 + 59.0 * std::sqrt(2.0) + 30.0) / 160.0, 1e-5);
  // Direction does not matter: the reversed segment lands in the same bin.
  const cv::Mat r = lineStructureOf({{80, 10, 0, 10}}, size, c);
  EXPECT_FLOAT_EQ(at(r, 0, 0, c), 0.5f);
  EXPECT_THROW(lineStructureOf(segs, cv::Size(0, 10), c), std::invalid_argument);
}

TEST(LineStructure, HoughFindsTheEdgesOfDrawnBoxesWhateverTheLight) {
  LineStructureConfig c;
  const cv::Mat bright = lineStructure(boxes(1.0), c);
  const double mass = cv::sum(bright)[0];
  ASSERT_GT(mass, 0.5);  // 2 x (120 + 80 + 110 + 100) px of edges over 560
  double axis = 0.0;     // horizontal (bin 0) and vertical (bin 6) in every band
  for (int b = 0; b < c.bands; ++b) axis += at(bright, b, 0, c) + at(bright, b, 6, c);
  EXPECT_GT(axis / mass, 0.95);
  // A third of the light: the edge thresholds follow the contrast, the structure stays.
  const cv::Mat dark = lineStructure(boxes(0.33), c);
  EXPECT_GT(structureSimilarity(bright, dark), 0.8);
  // A flat image has none.
  const cv::Mat flat = lineStructure(cv::Mat(240, 320, CV_8UC3, cv::Scalar(90, 90, 90)), c);
  EXPECT_EQ(cv::sum(flat)[0], 0.0);
  EXPECT_EQ(structureSimilarity(bright, flat), 0.0);
  EXPECT_THROW(lineStructure(cv::Mat(10, 10, CV_8UC1), c), std::invalid_argument);
}

TEST(LineStructure, SimilarityIsIntersectionOverTheLargerMass) {
  const cv::Mat a = (cv::Mat_<float>(1, 3) << 1, 0, 1);
  const cv::Mat b = (cv::Mat_<float>(1, 3) << 1, 1, 0);
  const cv::Mat half = (cv::Mat_<float>(1, 3) << 0.5f, 0, 0.5f);
  EXPECT_DOUBLE_EQ(structureSimilarity(a, a), 1.0);
  EXPECT_DOUBLE_EQ(structureSimilarity(a, b), 0.5);
  EXPECT_DOUBLE_EQ(structureSimilarity(a, half), 0.5);  // same shape, half the structure
  EXPECT_DOUBLE_EQ(structureSimilarity(half, a), 0.5);
  EXPECT_THROW(structureSimilarity(a, cv::Mat(1, 4, CV_32F, cv::Scalar(0))), std::invalid_argument);
}

TEST(LineStructure, CombineJoinsTheCandidatesAndWeighs) {
  StructureVoteConfig c;
  c.weight = 0.5;
  c.floor = 0.6;
  c.candidates = 2;
  const std::vector<FrameMatch> sift = {{2, 0.5}, {0, 0.2}};
  const std::vector<double> structure = {0.9, 0.5, 0.6, 0.7};
  // Structural candidates: frames 0 (0.9) and 3 (0.7); with SIFT's, frames 0, 2, 3.
  // Frame 0: 0.5 x 0.2 + 0.5 x (0.9 - 0.6) / 0.4 = 0.475; frame 2: 0.5 x 0.5 + 0 = 0.25 (its
  // structure is at the floor); frame 3: 0 + 0.5 x (0.7 - 0.6) / 0.4 = 0.125.
  const auto out = combineStructure(sift, structure, c, 10);
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(out[0].frame, 0);
  EXPECT_NEAR(out[0].similarity, 0.475, 1e-12);
  EXPECT_EQ(out[1].frame, 2);
  EXPECT_NEAR(out[1].similarity, 0.25, 1e-12);
  EXPECT_EQ(out[2].frame, 3);
  EXPECT_NEAR(out[2].similarity, 0.125, 1e-12);
  EXPECT_EQ(combineStructure(sift, structure, c, 2).size(), 2u);
  // Weight 0: the SIFT similarities unchanged.
  c.weight = 0.0;
  const auto plain = combineStructure(sift, structure, c, 10);
  EXPECT_EQ(plain[0].frame, 2);
  EXPECT_DOUBLE_EQ(plain[0].similarity, 0.5);
  EXPECT_DOUBLE_EQ(plain[1].similarity, 0.2);
  EXPECT_THROW(combineStructure({{7, 0.1}}, structure, c, 10), std::invalid_argument);
  c.weight = 1.5;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

TEST(RoomClassifier, StructuralCuesNeedStoredDescriptorsOfTheConfiguredSize) {
  RoomClassifierConfig cfg;
  cfg.structure.weight = 0.5;
  TrainingFrame f;
  f.image_id = 7;
  f.place = "lab";
  f.features = cv::Mat(3, 128, CV_32F, cv::Scalar(1));
  RoomClassifier rc(cfg);
  EXPECT_THROW(rc.setFrames({f}), std::invalid_argument);  // no descriptor
  f.structure = cv::Mat(1, 5, CV_32F, cv::Scalar(1));
  EXPECT_THROW(rc.setFrames({f}), std::invalid_argument);  // 5 values, 36 configured
}

TEST(RoomClassifier, StructureSeparatesRoomsThatSiftCannotTell) {
  // Two rooms whose images have no texture for SIFT, told apart by their lines alone: room
  // "hall" has horizontal structure, room "stairs" diagonal.
  LineStructureConfig lc;
  auto picture = [](bool diagonal, int shift) {
    cv::Mat img(240, 320, CV_8UC3, cv::Scalar(50, 50, 50));
    for (int i = 0; i < 4; ++i) {
      const int y = 30 + 50 * i + shift;
      if (diagonal)
        cv::line(img, {20, y}, {200, y + 120}, cv::Scalar(220, 220, 220), 3);
      else
        cv::line(img, {20, y}, {300, y}, cv::Scalar(220, 220, 220), 3);
    }
    return img;
  };
  std::vector<TrainingFrame> frames;
  for (int i = 0; i < 6; ++i) {
    TrainingFrame f;
    f.image_id = i;
    f.place = i < 3 ? "hall" : "stairs";
    f.features = cv::Mat(0, 128, CV_32F);
    f.structure = lineStructure(picture(i >= 3, 2 * i), lc);
    frames.push_back(f);
  }
  RoomClassifierConfig cfg;
  cfg.best_frames = 3;
  cfg.structure.weight = 0.5;
  RoomClassifier rc(cfg);
  rc.setFrames(frames);
  const RoomClassification hall = rc.classify(picture(false, 5));
  const RoomClassification stairs = rc.classify(picture(true, 5));
  EXPECT_EQ(hall.room, rc.roomIndex("hall"));
  EXPECT_EQ(stairs.room, rc.roomIndex("stairs"));
  // Without the structural vote nothing is classified (no SIFT similarity anywhere).
  cfg.structure.weight = 0.0;
  RoomClassifier plain(cfg);
  plain.setFrames(frames);
  EXPECT_EQ(plain.classify(picture(false, 5)).room, -1);
}
