// Whole-image descriptors: the invariances each is built for (gain and offset for the thumbnail,
// gain for the gradient histograms, the light's colour for the chromaticity), checked on textured
// images made here; the batch distance against a direct loop; and the traversal matcher on a
// route seen again under other light.
#include "adaptive_perception/places/global_descriptor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>

#include "adaptive_perception/places/traversal_matcher.h"

namespace places = adaptive_perception::places;

namespace {

/// A smooth random texture (blurred noise), bgr8, values well inside [40, 200].
cv::Mat texture(int seed, int w = 256, int h = 128) {
  cv::Mat img(h, w, CV_8UC3);
  cv::RNG rng(seed);
  rng.fill(img, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(img, img, cv::Size(0, 0), 3.0);
  cv::normalize(img, img, 40, 200, cv::NORM_MINMAX);
  return img;
}

double distance(const cv::Mat& a, const cv::Mat& b, places::DescriptorKind k) {
  const places::GlobalDescriptorConfig c;
  return places::descriptorDistances(places::computeDescriptor(a, k, c),
                                     places::computeDescriptor(b, k, c))[0];
}

TEST(GlobalDescriptor, LengthsMatchTheConfig) {
  const places::GlobalDescriptorConfig c;
  for (int k = 0; k < places::kNumDescriptorKinds; ++k) {
    const auto kind = static_cast<places::DescriptorKind>(k);
    EXPECT_EQ(places::computeDescriptor(texture(1), kind, c).cols, c.length(kind))
        << places::descriptorName(kind);
    EXPECT_EQ(places::descriptorFromName(places::descriptorName(kind)), kind);
  }
  EXPECT_EQ(c.length(places::DescriptorKind::kThumbnail), 64 * 32);
  EXPECT_EQ(c.length(places::DescriptorKind::kGradient), 7 * 3 * 36);
  EXPECT_THROW(places::descriptorFromName("sift"), std::invalid_argument);
}

TEST(GlobalDescriptor, ThumbnailIgnoresGainAndOffset) {
  const cv::Mat a = texture(1), other = texture(2);
  cv::Mat darker;
  a.convertTo(darker, -1, 0.5, 10.0);  // half the gain, a small offset: no clipping
  const double same = distance(a, darker, places::DescriptorKind::kThumbnail);
  const double diff = distance(a, other, places::DescriptorKind::kThumbnail);
  EXPECT_GT(diff, 10.0 * same);
}

TEST(GlobalDescriptor, GradientIgnoresGain) {
  const cv::Mat a = texture(3), other = texture(4);
  cv::Mat brighter;
  a.convertTo(brighter, -1, 1.25, 0.0);
  const double same = distance(a, brighter, places::DescriptorKind::kGradient);
  const double diff = distance(a, other, places::DescriptorKind::kGradient);
  EXPECT_GT(diff, 5.0 * same);
}

TEST(GlobalDescriptor, ChromaticityIgnoresTheLightsColour) {
  const cv::Mat a = texture(5), other = texture(6);
  cv::Mat warm;
  a.convertTo(warm, CV_32FC3);
  warm = warm.mul(cv::Scalar(0.7, 1.0, 1.2));  // bluish to reddish light, per-channel gains
  warm.convertTo(warm, CV_8UC3);
  const double same = distance(a, warm, places::DescriptorKind::kChromaticity);
  const double diff = distance(a, other, places::DescriptorKind::kChromaticity);
  EXPECT_GT(diff, 3.0 * same);
}

TEST(GlobalDescriptor, GreyImagesHaveOneChromaticity) {
  cv::Mat grey1, grey2;
  cv::cvtColor(texture(7), grey1, cv::COLOR_BGR2GRAY);
  cv::cvtColor(texture(8), grey2, cv::COLOR_BGR2GRAY);
  EXPECT_NEAR(distance(grey1, grey2, places::DescriptorKind::kChromaticity), 0.0, 1e-9);
  // mono8 and its bgr8 copy give the same descriptors.
  cv::Mat bgr;
  cv::cvtColor(grey1, bgr, cv::COLOR_GRAY2BGR);
  for (int k = 0; k < places::kNumDescriptorKinds; ++k)
    EXPECT_NEAR(distance(grey1, bgr, static_cast<places::DescriptorKind>(k)), 0.0, 1e-9) << k;
}

TEST(GlobalDescriptor, BatchDistanceIsTheMeanAbsoluteDifference) {
  cv::Mat stored(5, 37, CV_8UC1), query(1, 37, CV_8UC1);
  cv::RNG rng(9);
  rng.fill(stored, cv::RNG::UNIFORM, 0, 256);
  rng.fill(query, cv::RNG::UNIFORM, 0, 256);
  const std::vector<float> d = places::descriptorDistances(query, stored);
  for (int r = 0; r < 5; ++r) {
    double s = 0.0;
    for (int c = 0; c < 37; ++c) s += std::abs(int(query.at<uchar>(0, c)) - stored.at<uchar>(r, c));
    EXPECT_NEAR(d[r], s / 37.0, 1e-4);
  }
  EXPECT_THROW(places::descriptorDistances(cv::Mat(1, 36, CV_8UC1), stored), std::invalid_argument);
}

TEST(GlobalDescriptor, RejectsBadImagesAndSettings) {
  const places::GlobalDescriptorConfig c;
  EXPECT_THROW(places::computeDescriptor(cv::Mat(), places::DescriptorKind::kThumbnail, c),
               std::invalid_argument);
  EXPECT_THROW(places::computeDescriptor(cv::Mat(10, 10, CV_32FC1, 0.0f),
                                         places::DescriptorKind::kGradient, c),
               std::invalid_argument);
  places::GlobalDescriptorConfig bad;
  bad.patch_px = 5;  // does not divide 64
  EXPECT_THROW(bad.validate(), std::invalid_argument);
  bad = {};
  bad.hog_width_px = 100;  // not a multiple of 32
  EXPECT_THROW(bad.validate(), std::invalid_argument);
}

TEST(TraversalMatcher, RouteSeenAgainUnderOtherLight) {
  // A route of 40 views panning over one wide texture; the query drives it again under dimmer,
  // warmer light with sensor noise, one view shifted by a pixel.
  const cv::Mat world = texture(11, 256 + 40 * 12, 128);
  places::TraversalMatcherConfig cfg;
  places::ReferenceTraversal refs(cfg.descriptor);
  for (int i = 0; i < 40; ++i)
    refs.add(places::computeDescriptors(world(cv::Rect(i * 12, 0, 256, 128)), cfg.descriptor));
  cv::RNG rng(12);
  for (const std::string method : {"thumbnail", "gradient", "fused", "sequence"}) {
    cfg.method = method;
    places::TraversalMatcher m(refs, cfg);
    int right = 0;
    for (int i = 0; i < 40; ++i) {
      cv::Mat q = world(cv::Rect(i * 12 + 1, 0, 256, 128)).clone(), noise(q.size(), CV_8UC3);
      q.convertTo(q, -1, 0.6, 5.0);
      q = q.mul(cv::Scalar(0.8, 1.0, 1.1));
      rng.fill(noise, cv::RNG::NORMAL, 0, 3);
      q += noise;
      const std::vector<float>& s = m.add(places::computeDescriptors(q, cfg.descriptor));
      right += std::min_element(s.begin(), s.end()) - s.begin() == i;
    }
    EXPECT_EQ(right, 40) << method;
  }
}

TEST(TraversalMatcher, FusedDistancesAreWeightedZScores) {
  places::TraversalMatcherConfig cfg;
  places::ReferenceTraversal refs(cfg.descriptor);
  for (int i = 0; i < 6; ++i) refs.add(places::computeDescriptors(texture(20 + i), cfg.descriptor));
  const places::ImageDescriptors q = places::computeDescriptors(texture(30), cfg.descriptor);
  const auto z = [&](places::DescriptorKind k) {
    std::vector<float> d = places::descriptorDistances(q.rows[static_cast<int>(k)], refs.rows(k));
    double mean = 0.0, sq = 0.0;
    for (float v : d) mean += v / 6.0;
    for (float v : d) sq += (v - mean) * (v - mean) / 6.0;
    for (float& v : d) v = static_cast<float>((v - mean) / std::sqrt(sq));
    return d;
  };
  const std::vector<float> zt = z(places::DescriptorKind::kThumbnail);
  const std::vector<float> zg = z(places::DescriptorKind::kGradient);
  const std::vector<float> f = places::cueDistances(refs, q, {1.0, 3.0, 0.0});
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(f[j], (zt[j] + 3.0 * zg[j]) / 4.0, 1e-4);
  const std::vector<float> t =
      places::cueDistances(refs, q, places::cueWeights("thumbnail", places::FusionWeights{}));
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(t[j], zt[j], 1e-4);
  EXPECT_THROW(places::cueWeights("nearest", {}), std::invalid_argument);
  cfg.method = "nearest";
  EXPECT_THROW(cfg.validate(), std::invalid_argument);
  cfg.method = "fused";
  cfg.fusion = {0.0, 0.0, 0.0};
  EXPECT_THROW(cfg.validate(), std::invalid_argument);
  places::ReferenceTraversal empty(cfg.descriptor);
  places::TraversalMatcher none(empty, {});
  EXPECT_THROW(none.add(q), std::invalid_argument);
}

}  // namespace
