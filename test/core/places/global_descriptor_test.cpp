// Whole-image descriptors: the invariances each is built for (gain and offset for the thumbnail,
// gain for the gradient histograms, the light's colour for the chromaticity), checked on textured
// images made here; the batch distance against a direct loop; and the traversal matcher on a
// route seen again under other light.
#include "adaptive_perception/places/global_descriptor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>

#include "adaptive_perception/places/feature_index.h"
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

/// The image under other light: per-channel gains (b, g, r), then an offset (rounded to bgr8).
std::function<cv::Mat(const cv::Mat&)> gains(double b, double g, double r, double offset = 0.0) {
  return [=](const cv::Mat& img) {
    cv::Mat f;
    img.convertTo(f, CV_32FC3);
    f = f.mul(cv::Scalar(b, g, r)) + cv::Scalar::all(offset);
    cv::Mat out;
    f.convertTo(out, CV_8UC3);
    return out;
  };
}

/// How many times farther another scene (texture(seed + 1)) is from texture(seed) than the same
/// scene under other light: large for a descriptor that ignores that change of light.
double otherSceneOverRelit(places::DescriptorKind k, int seed,
                           const std::function<cv::Mat(const cv::Mat&)>& relight) {
  const cv::Mat a = texture(seed);
  return distance(a, texture(seed + 1), k) / distance(a, relight(a), k);
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
  // Half the gain, a small offset: no clipping.
  EXPECT_GT(otherSceneOverRelit(places::DescriptorKind::kThumbnail, 1, gains(0.5, 0.5, 0.5, 10.0)),
            10.0);
}

TEST(GlobalDescriptor, GradientIgnoresGain) {
  EXPECT_GT(otherSceneOverRelit(places::DescriptorKind::kGradient, 3, gains(1.25, 1.25, 1.25)),
            5.0);
}

TEST(GlobalDescriptor, ChromaticityIgnoresTheLightsColour) {
  // Bluish to reddish light: per-channel gains.
  EXPECT_GT(otherSceneOverRelit(places::DescriptorKind::kChromaticity, 5, gains(0.7, 1.0, 1.2)),
            3.0);
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

TEST(GlobalDescriptor, LayoutIgnoresAnyMonotonicChangeOfBrightness) {
  // Equalisation ranks the grey levels: a gamma curve and a gain (no clipping) keep every rank,
  // so the layout hardly moves (the grey conversion and the resize round differently), while
  // another scene's layout is far.
  // Scenes with a large-scale layout (blurred far more than texture() does).
  const auto scene = [](int seed) {
    cv::Mat img = texture(seed);
    cv::GaussianBlur(img, img, cv::Size(0, 0), 20.0);
    cv::normalize(img, img, 30, 220, cv::NORM_MINMAX);
    return img;
  };
  const cv::Mat a = scene(10), other = scene(11);
  cv::Mat lut(1, 256, CV_8UC1);
  for (int v = 0; v < 256; ++v)
    lut.at<uchar>(0, v) = cv::saturate_cast<uchar>(255.0 * std::pow(v / 255.0, 1.8));
  cv::Mat night;
  cv::LUT(a, lut, night);
  night.convertTo(night, -1, 0.8, 0.0);
  const double same = distance(a, night, places::DescriptorKind::kLayout);
  const double diff = distance(a, other, places::DescriptorKind::kLayout);
  EXPECT_GT(diff, 5.0 * same) << same << " " << diff;
}

TEST(GlobalDescriptor, OmniLayoutIgnoresTheRobotTurning) {
  // A ring image (square, ring about the image centre); the robot turning on the spot rotates it.
  // A quarter turn moves every pixel onto another pixel exactly, and the 16 sectors by 4.
  cv::Mat img = texture(12, 200, 200), other = texture(13, 200, 200);
  places::GlobalDescriptorConfig c;
  c.omni_ring = places::MaskConfig::parse("ring:100,100,20,95");
  cv::Mat turned;
  cv::rotate(img, turned, cv::ROTATE_90_CLOCKWISE);
  const auto d = [&](const cv::Mat& x, const cv::Mat& y) -> double {
    return places::descriptorDistances(
        places::computeDescriptor(x, places::DescriptorKind::kLayout, c),
        places::computeDescriptor(y, places::DescriptorKind::kLayout, c))[0];
  };
  EXPECT_EQ(places::computeDescriptor(img, places::DescriptorKind::kLayout, c).cols,
            (16 / 2 + 1) * 8);
  EXPECT_LT(d(img, turned), 0.5);  // rounding of the stored bytes and of sector boundaries only
  EXPECT_GT(d(img, other), 10.0 * std::max(0.05, d(img, turned)));
  // The perspective regions are not built for it: a quarter turn moves them.
  EXPECT_GT(distance(img, turned, places::DescriptorKind::kLayout),
            5.0 * std::max(0.05, d(img, turned)));
  // An omni configuration says so in its settings string (a database records it).
  EXPECT_NE(c.toString().find("layout=sectors16@ring:"), std::string::npos) << c.toString();
  EXPECT_NE(places::GlobalDescriptorConfig().toString().find("layout=regions4x2/8"),
            std::string::npos);
  EXPECT_EQ(places::descriptorConfigForMask(c.omni_ring).toString(), c.toString());
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
  std::vector<cv::Mat> sift;
  const auto describe = [&](const cv::Mat& view) {
    places::ImageDescriptors d = places::computeDescriptors(view, cfg.descriptor);
    d.sift = places::extractSift(view, places::SiftConfig());
    return d;
  };
  for (int i = 0; i < 40; ++i) {
    const places::ImageDescriptors d = describe(world(cv::Rect(i * 12, 0, 256, 128)));
    refs.add(d);
    sift.push_back(d.sift);
  }
  refs.learnWords(sift);
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
      const std::vector<float>& s = m.add(describe(q));
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

TEST(TraversalMatcher, WordsRecogniseDistinctViewsUnderOtherLight) {
  // Twenty different views (the words tell views apart by what they hold: the panning route above,
  // one statistically uniform texture, is not for them), seen again dimmer, warmer and noisy.
  places::TraversalMatcherConfig cfg;
  cfg.method = "words";
  places::ReferenceTraversal refs(cfg.descriptor);
  std::vector<cv::Mat> sift;
  for (int i = 0; i < 20; ++i) {
    refs.add(places::computeDescriptors(texture(100 + i), cfg.descriptor));
    sift.push_back(places::extractSift(texture(100 + i), places::SiftConfig()));
  }
  refs.learnWords(sift);
  places::TraversalMatcher m(refs, cfg);
  cv::RNG rng(5);
  int right = 0;
  for (int i = 0; i < 20; ++i) {
    cv::Mat q = texture(100 + i), noise(q.size(), CV_8UC3);
    q.convertTo(q, -1, 0.6, 5.0);
    q = q.mul(cv::Scalar(0.8, 1.0, 1.1));
    rng.fill(noise, cv::RNG::NORMAL, 0, 3);
    q += noise;
    places::ImageDescriptors d = places::computeDescriptors(q, cfg.descriptor);
    d.sift = places::extractSift(q, places::SiftConfig());
    const std::vector<float>& s = m.add(d);
    right += std::min_element(s.begin(), s.end()) - s.begin() == i;
  }
  // Measured 19 of 20 (a descriptor whose light changed can fall into a neighbouring word); the
  // whole-image cues get all 20.
  EXPECT_GE(right, 18);
}

TEST(TraversalMatcher, WordsJoinTheFusionWithTheirWeight) {
  places::TraversalMatcherConfig cfg;
  places::ReferenceTraversal refs(cfg.descriptor);
  std::vector<cv::Mat> sift;
  for (int i = 0; i < 6; ++i) {
    refs.add(places::computeDescriptors(texture(40 + i), cfg.descriptor));
    sift.push_back(places::extractSift(texture(40 + i), places::SiftConfig()));
  }
  places::ImageDescriptors q = places::computeDescriptors(texture(43), cfg.descriptor);
  cfg.method = "words";
  places::TraversalMatcher before(refs, cfg);
  EXPECT_THROW(before.add(q), std::invalid_argument) << "no vocabulary yet";
  EXPECT_THROW(refs.learnWords({sift[0]}), std::invalid_argument) << "one matrix per reference";
  refs.learnWords(sift);
  places::TraversalMatcher words(refs, cfg);
  EXPECT_THROW(words.add(q), std::invalid_argument) << "a query without SIFT";
  q.sift = places::extractSift(texture(43), places::SiftConfig());
  const std::vector<float> w = words.add(q);
  EXPECT_EQ(std::min_element(w.begin(), w.end()) - w.begin(), 3) << "the same image";
  // fused with words: (rest * cues + words_weight * words) / (rest + words_weight), where the
  // cues are the weighted z-scores of the other descriptors (rest = their weights' sum).
  cfg.method = "fused";
  cfg.fusion.words = 2.0;
  places::TraversalMatcher fused(refs, cfg);
  const std::vector<float> f = fused.add(q);
  const std::vector<float> cues =
      places::cueDistances(refs, q, places::cueWeights("fused", places::FusionWeights{}));
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(f[j], (2.0 * cues[j] + 2.0 * w[j]) / 4.0, 1e-5);
}

}  // namespace
