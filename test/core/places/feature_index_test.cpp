// SIFT room classification: the vote and its 60% rule on the paper's Tables 1-2, the ImageCLEF
// score, the ratio-test similarity, and the indexed matcher against brute force.
#include "adaptive_perception/places/feature_index.h"

#include <gtest/gtest.h>

#include <numeric>
#include <opencv2/imgproc.hpp>
#include <random>
#include <set>

using namespace adaptive_perception::places;

TEST(RoomVote, PaperTablesOneAndTwo) {
  // Rooms: PA 0, CR 1, BO 2, EO 3, KT 4. Table 1's 11 frames and weights.
  const std::vector<double> w = {0.07, 0.42, 0.34, 0.14, 0.48, 0.87, 0.24, 0.12, 0.04, 0.45, 0.05};
  const std::vector<int> room = {1, 0, 0, 1, 0, 0, 1, 1, 2, 0, 2};
  std::vector<FrameMatch> best;
  for (int i = 0; i < 11; ++i) best.push_back({i, w[i]});
  const RoomVote v = voteRooms(best, room, 5);
  // Table 2: PA 2.56, CR 0.57, BO 0.09; 2.56 / 3.22 = 0.795 > 0.6: Printer Area.
  EXPECT_NEAR(v.sums[0], 2.56, 1e-9);
  EXPECT_NEAR(v.sums[1], 0.57, 1e-9);
  EXPECT_NEAR(v.sums[2], 0.09, 1e-9);
  EXPECT_EQ(v.sums[3], 0.0);
  EXPECT_EQ(v.room, 0);
  EXPECT_NEAR(v.share, 2.56 / 3.22, 1e-9);
  // Move two PA frames to CR: PA 1.69, CR 1.44 of 3.22: 52% < 60%, not classified.
  std::vector<int> room2 = room;
  room2[5] = 1;
  const RoomVote u = voteRooms(best, room2, 5);
  EXPECT_EQ(u.room, -1);
  EXPECT_NEAR(u.share, 1.69 / 3.22, 1e-9);
  EXPECT_EQ(voteRooms({}, room, 5).room, -1);
  EXPECT_THROW(voteRooms({{20, 0.5}}, room, 5), std::invalid_argument);
}

TEST(ClefScore, PlusOneMinusHalfZero) {
  ClefScore s;
  for (int i = 0; i < 3; ++i) s.add(1, 1);
  s.add(2, 1);
  s.add(0, 1);
  s.add(-1, 1);
  EXPECT_EQ(s.correct, 3);
  EXPECT_EQ(s.misclassified, 2);
  EXPECT_EQ(s.not_classified, 1);
  EXPECT_DOUBLE_EQ(s.score(), 2.0);
}

namespace {
cv::Mat randomDescriptors(int n, std::mt19937& gen) {
  std::uniform_real_distribution<float> u(0.0f, 255.0f);
  cv::Mat d(n, 128, CV_32F);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < 128; ++c) d.at<float>(r, c) = u(gen);
  return d;
}
cv::Mat jitter(const cv::Mat& d, float sd, std::mt19937& gen) {
  std::normal_distribution<float> g(0.0f, sd);
  cv::Mat out = d.clone();
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < 128; ++c) out.at<float>(r, c) += g(gen);
  return out;
}
}  // namespace

TEST(FrameSimilarity, RatioTestShares) {
  std::mt19937 gen(1);
  const cv::Mat a = randomDescriptors(50, gen);
  EXPECT_DOUBLE_EQ(frameSimilarity(a, a), 1.0);
  EXPECT_GT(frameSimilarity(jitter(a, 5.0f, gen), a), 0.95);
  EXPECT_LT(frameSimilarity(randomDescriptors(50, gen), a), 0.1);
  // Half of the query comes from the frame.
  cv::Mat half;
  cv::vconcat(a.rowRange(0, 25), randomDescriptors(25, gen), half);
  EXPECT_NEAR(frameSimilarity(half, a), 0.5, 0.06);
  EXPECT_EQ(frameSimilarity(cv::Mat(), a), 0.0);
  EXPECT_EQ(frameSimilarity(a, a.rowRange(0, 1)), 0.0);
}

TEST(FeatureIndex, AgreesWithBruteForceOnTheTopFrames) {
  // 8 scenes, each seen in 5 frames (jittered copies of 80 scene descriptors, 60 kept at random
  // plus 20 of clutter). A query from scene 3: brute force ranks scene 3's frames first.
  std::mt19937 gen(7);
  std::vector<cv::Mat> scenes;
  for (int s = 0; s < 8; ++s) scenes.push_back(randomDescriptors(80, gen));
  FeatureIndex index;
  std::vector<int> scene_of;
  for (int copy = 0; copy < 5; ++copy)
    for (int s = 0; s < 8; ++s) {
      std::vector<int> rows(80);
      std::iota(rows.begin(), rows.end(), 0);
      std::shuffle(rows.begin(), rows.end(), gen);
      cv::Mat f(0, 128, CV_32F);
      for (int i = 0; i < 60; ++i) f.push_back(scenes[s].row(rows[i]));
      f.push_back(randomDescriptors(20, gen));
      index.addFrame(jitter(f, 4.0f, gen));
      scene_of.push_back(s);
    }
  EXPECT_THROW(index.topFrames(scenes[0], 5), std::logic_error);
  index.build();
  const cv::Mat query = jitter(scenes[3].rowRange(0, 70), 4.0f, gen);
  const auto brute = index.bruteForce(query, 5);
  const auto fast = index.topFrames(query, 5);
  ASSERT_EQ(fast.size(), 5u);
  std::set<int> a, b;
  for (int i = 0; i < 5; ++i) {
    a.insert(brute[i].frame);
    b.insert(fast[i].frame);
    EXPECT_EQ(scene_of[brute[i].frame], 3);
    EXPECT_DOUBLE_EQ(fast[i].similarity, brute[i].similarity);
  }
  EXPECT_EQ(a, b);
  EXPECT_GT(fast[0].similarity, 0.5);
}

TEST(Sift, ExtractsFromATexturedImageAndNothingFromAFlatOne) {
  cv::Mat img(120, 160, CV_8UC3, cv::Scalar(90, 90, 90));
  std::mt19937 gen(2);
  std::uniform_int_distribution<int> u(0, 255);
  for (int i = 0; i < 40; ++i)
    cv::rectangle(img, cv::Rect{u(gen) % 150, u(gen) % 110, 5 + u(gen) % 30, 5 + u(gen) % 30},
                  cv::Scalar{double(u(gen)), double(u(gen)), double(u(gen))}, cv::FILLED);
  SiftConfig cfg;
  const cv::Mat d = extractSift(img, cfg);
  EXPECT_GT(d.rows, 20);
  EXPECT_LE(d.rows, cfg.max_features + 10);  // OpenCV keeps ties at the cut
  EXPECT_EQ(d.cols, 128);
  EXPECT_EQ(extractSift(cv::Mat(120, 160, CV_8UC3, cv::Scalar(90, 90, 90)), cfg).rows, 0);
  // The same image matches itself entirely.
  EXPECT_DOUBLE_EQ(frameSimilarity(d, d), 1.0);
}
