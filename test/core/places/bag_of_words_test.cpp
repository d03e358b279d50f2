// The bag of SIFT words on descriptors drawn about four well-separated centres, so that k-means
// must find exactly those words and every distance can be worked out by hand from tf-idf.
#include "adaptive_perception/places/bag_of_words.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <random>
#include <set>

#include "../refusal.h"

using namespace adaptive_perception::places;

namespace {

// A descriptor near centre c (0..3): 100 in dimensions 32c..32c+31, plus noise of +-2.
cv::Mat near(int c, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  cv::Mat d(1, 128, CV_32F);
  for (int i = 0; i < 128; ++i) d.at<float>(i) = (i / 32 == c ? 100.0f : 0.0f) + u(rng);
  return d;
}

cv::Mat image(const std::vector<int>& centres, std::mt19937& rng) {
  cv::Mat f(0, 128, CV_32F);
  for (int c : centres) f.push_back(near(c, rng));
  return f;
}

BagOfWordsConfig fourWords() {
  BagOfWordsConfig c;
  c.words = 4;
  c.max_training_descriptors = 1000;
  return c;
}

}  // namespace

TEST(BagOfWords, KMeansFindsTheFourCentres) {
  std::mt19937 rng(1);
  std::vector<cv::Mat> refs;
  for (int r = 0; r < 10; ++r) refs.push_back(image({0, 1, 2, 3, 0, 1, 2, 3}, rng));
  const BagOfWords bow(refs, fourWords());
  ASSERT_EQ(bow.words(), 4);
  std::set<int> words;
  for (int c = 0; c < 4; ++c) {
    const std::vector<int> w = bow.assign(image({c, c, c}, rng));
    ASSERT_EQ(w.size(), 3u);
    EXPECT_EQ(w[0], w[1]);
    EXPECT_EQ(w[1], w[2]);
    words.insert(w[0]);
  }
  EXPECT_EQ(words.size(), 4u) << "each centre is its own word";
}

TEST(BagOfWords, DistancesAreOneMinusTheCosineOfTfIdf) {
  std::mt19937 rng(2);
  // A holds words {0, 0, 1}, B {2, 3}, C {0, 2}. Document frequencies over N = 3 references:
  // words 0 and 2 in two (idf ln 1.5), words 1 and 3 in one (idf ln 3).
  const std::vector<cv::Mat> refs = {image({0, 0, 1}, rng), image({2, 3}, rng), image({0, 2}, rng)};
  const BagOfWords bow(refs, fourWords());
  const std::vector<float> d = bow.distances(image({0, 0, 1}, rng));
  ASSERT_EQ(d.size(), 3u);
  const double l15 = std::log(1.5), l3 = std::log(3.0);
  // A = (2 l15, l3, 0, 0), C = (l15, 0, l15, 0): cos = 2 l15^2 / (|A| |C|).
  const double cos_ac = 2 * l15 * l15 / (std::sqrt(4 * l15 * l15 + l3 * l3) * std::sqrt(2.0) * l15);
  EXPECT_NEAR(d[0], 0.0, 1e-6);
  EXPECT_NEAR(d[1], 1.0, 1e-6) << "no word in common";
  EXPECT_NEAR(d[2], 1.0 - cos_ac, 1e-6);
  // An image without features shares nothing with any reference.
  for (float x : bow.distances(cv::Mat(0, 128, CV_32F))) EXPECT_FLOAT_EQ(x, 1.0f);
}

TEST(BagOfWords, DeterministicAndLeavesTheCallersGeneratorAlone) {
  std::mt19937 rng(3);
  std::vector<cv::Mat> refs;
  for (int r = 0; r < 6; ++r) refs.push_back(image({r % 4, (r + 1) % 4, (r + 2) % 4}, rng));
  cv::theRNG().state = 42;
  const BagOfWords a(refs, fourWords());
  EXPECT_EQ(cv::theRNG().state, 42u);
  const BagOfWords b(refs, fourWords());
  EXPECT_EQ(cv::norm(a.vocabulary(), b.vocabulary(), cv::NORM_INF), 0.0);
}

TEST(BagOfWords, FewDescriptorsAreTheirOwnVocabularyAndBadInputIsNamed) {
  std::mt19937 rng(4);
  BagOfWordsConfig c = fourWords();
  c.words = 50;
  c.max_training_descriptors = 50;
  const BagOfWords small({image({0, 1}, rng), image({2}, rng)}, c);
  EXPECT_EQ(small.words(), 3);
  EXPECT_THROW(BagOfWords({cv::Mat(0, 128, CV_32F)}, c), std::invalid_argument);
  EXPECT_THROW(BagOfWords({cv::Mat::zeros(3, 64, CV_32F)}, c), std::invalid_argument);
  EXPECT_THROW(small.distances(cv::Mat::zeros(2, 128, CV_8U)), std::invalid_argument);
  c.max_training_descriptors = 10;
  EXPECT_TRUE(adaptive_perception::test_support::refusedNaming([&] { c.validate(); },
                                                               "max_training_descriptors"));
}
