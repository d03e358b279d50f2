// Histogram distances on hand-computed histograms, eqs. (5)-(7) on a small hand case, the
// confidence-based selection, and the topological Bayes filter.
#include "adaptive_perception/places/place_matcher.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "adaptive_perception/places/histogram_distance.h"
#include "adaptive_perception/places/place_filter.h"

using namespace adaptive_perception::places;

namespace {
const std::vector<Distance> kAll = parseDistances("all");
}

TEST(Distances, HandComputedBands) {
  const float h[4] = {0.5f, 0.5f, 0.0f, 0.0f};
  const float k[4] = {0.25f, 0.25f, 0.5f, 0.0f};
  // chi-square: 0.25^2 / 0.25 * 2 + 0.5^2 / 0.5 + 0 (both empty) = 1.
  EXPECT_NEAR(bandDistance(Distance::kChiSquare, h, k, 4), 1.0, 1e-9);
  // Jeffrey: 2 * [0.5 log2(1 / 0.75) + 0.25 log2(0.5 / 0.75)] + 0.5 log2(2) = 0.6225562.
  const double jd = 2 * (0.5 * std::log2(1 / 0.75) + 0.25 * std::log2(0.5 / 0.75)) + 0.5;
  EXPECT_NEAR(bandDistance(Distance::kJeffrey, h, k, 4), jd, 1e-7);
  EXPECT_NEAR(jd, 0.6225562, 1e-6);
  // KS, eq. (4): max bin-wise |h - k| = 0.5; cumulative: (0.5, 1, 1, 1) vs (0.25, 0.5, 1, 1) ->
  // 0.5.
  EXPECT_NEAR(bandDistance(Distance::kKolmogorovSmirnov, h, k, 4), 0.5, 1e-9);
  EXPECT_NEAR(bandDistance(Distance::kKsCumulative, h, k, 4), 0.5, 1e-9);
  // Intersection: 1 - (0.25 + 0.25) / 1 = 0.5.
  EXPECT_NEAR(bandDistance(Distance::kIntersection, h, k, 4), 0.5, 1e-9);
  // Cumulative and bin-wise KS differ when mass moves far: (1, 0, 0) vs (0, 0, 1).
  const float a[3] = {1, 0, 0}, b[3] = {0, 0, 1};
  EXPECT_NEAR(bandDistance(Distance::kKolmogorovSmirnov, a, b, 3), 1.0, 1e-9);
  EXPECT_NEAR(bandDistance(Distance::kKsCumulative, a, b, 3), 1.0, 1e-9);
  const float c[3] = {0.5, 0.5, 0}, e[3] = {0, 0.5, 0.5};
  EXPECT_NEAR(bandDistance(Distance::kKolmogorovSmirnov, c, e, 3), 0.5, 1e-9);
  EXPECT_NEAR(bandDistance(Distance::kKsCumulative, c, e, 3), 0.5, 1e-9);
}

TEST(Distances, EmptyTrainingBinRuleForChiSquare) {
  // K empty where H is not: the documented rule charges h: 0.5^2 / 1 + 0.5 = 0.75.
  const float h[2] = {0.5f, 0.5f}, k[2] = {1.0f, 0.0f};
  EXPECT_NEAR(bandDistance(Distance::kChiSquare, h, k, 2), 0.75, 1e-9);
  EXPECT_TRUE(std::isfinite(bandDistance(Distance::kChiSquare, k, h, 2)));
}

TEST(Distances, IdenticalGiveZeroAndSymmetryWhereExpected) {
  const float h[6] = {0.1f, 0.2f, 0.7f, 0.3f, 0.3f, 0.4f};
  const float k[6] = {0.4f, 0.4f, 0.2f, 0.1f, 0.0f, 0.9f};
  for (Distance d : kAll) {
    EXPECT_NEAR(bandDistance(d, h, h, 6), 0.0, 1e-7) << distanceName(d);
    EXPECT_GT(bandDistance(d, h, k, 6), 0.0) << distanceName(d);
  }
  for (Distance d : {Distance::kJeffrey, Distance::kKolmogorovSmirnov, Distance::kKsCumulative,
                     Distance::kIntersection})
    EXPECT_NEAR(bandDistance(d, h, k, 6), bandDistance(d, k, h, 6), 1e-7) << distanceName(d);
  EXPECT_NE(bandDistance(Distance::kChiSquare, h, k, 6),
            bandDistance(Distance::kChiSquare, k, h, 6));
  // Band average: three bands with distances a, b, c give (a + b + c) / 3.
  const float hh[6] = {1, 0, 1, 0, 0.5, 0.5}, kk[6] = {0, 1, 1, 0, 0.5, 0.5};
  EXPECT_NEAR(histogramDistance(Distance::kKolmogorovSmirnov, hh, kk, 2), 1.0 / 3, 1e-9);
  EXPECT_EQ(distanceFromName("ks"), Distance::kKolmogorovSmirnov);
  EXPECT_THROW(distanceFromName("emd"), std::invalid_argument);
  EXPECT_EQ(parseDistances("paper").size(), 3u);
}

TEST(Distances, FastQueryAgreesWithTheDefinition) {
  // HistogramQuery (single precision, four bins at a time) against bandDistance (double, bin by
  // bin) on random histograms with a third of the bins empty, bin counts that are and are not
  // multiples of 4 (the scalar tail), and identical pairs.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int bins : {4, 7, 16, 61, 256}) {
    auto random = [&] {
      std::vector<float> x(3 * bins);
      for (int band = 0; band < 3; ++band) {
        float sum = 0.0f;
        for (int i = 0; i < bins; ++i) {
          const float v = u(rng) < 0.33f ? 0.0f : u(rng);
          x[band * bins + i] = v;
          sum += v;
        }
        if (sum == 0.0f) x[band * bins] = sum = 1.0f;
        for (int i = 0; i < bins; ++i) x[band * bins + i] /= sum;
      }
      return x;
    };
    for (int trial = 0; trial < 20; ++trial) {
      const std::vector<float> h = random(), k = trial % 5 == 0 ? h : random();
      for (Distance d : kAll) {
        const HistogramQuery query(d, h.data(), bins);
        const double fast = query(k.data(), HistogramQuery::storedTerms(k.data(), bins));
        EXPECT_NEAR(fast, histogramDistance(d, h.data(), k.data(), bins), 1e-5)
            << distanceName(d) << " bins " << bins << " trial " << trial;
      }
    }
  }
}

namespace {
// One-band-per-space histograms over 2 bins: band 0 = (p, 1 - p), bands 1, 2 = (1, 0).
ImageHistograms hist(float p) {
  ImageHistograms h;
  h.bins = 2;
  h.spaces[0] = {p, 1 - p, 1, 0, 1, 0};
  return h;
}
}  // namespace

TEST(PlaceMatcher, NodeDistanceIsTheMeanOverTrainingImages) {
  PlaceIndex index(2);
  const int a = index.addPlace("kitchen");
  const int b = index.addPlace("corridor");
  EXPECT_EQ(index.addPlace("kitchen"), a);
  index.addImage(a, hist(1.0f));
  index.addImage(a, hist(0.6f));
  index.addImage(b, hist(0.0f));
  EXPECT_EQ(index.imageCount(a, 0), 2);
  // Test p = 0.8. KS band 0: |0.8 - 1| = 0.2 and |0.8 - 0.6| = 0.2, bands 1-2: 0; eq. (5): D_a =
  // (0.2 / 3 + 0.2 / 3) / 2 = 0.0667; D_b = 0.8 / 3.
  const auto d = index.nodeDistances(0, Distance::kKolmogorovSmirnov, hist(0.8f));
  ASSERT_EQ(d.size(), 2u);
  EXPECT_NEAR(d[a], 0.2 / 3, 1e-6);
  EXPECT_NEAR(d[b], 0.8 / 3, 1e-6);
  // A place with no image is infinitely far; a space the test lacks is an error.
  index.addPlace("office");
  EXPECT_TRUE(std::isinf(index.nodeDistances(0, Distance::kKolmogorovSmirnov, hist(0.8f))[2]));
  EXPECT_THROW(index.nodeDistances(3, Distance::kKolmogorovSmirnov, hist(0.8f)),
               std::invalid_argument);
  ImageHistograms wrong = hist(0.5f);
  wrong.bins = 4;
  EXPECT_THROW(index.addImage(a, wrong), std::invalid_argument);
}

TEST(PlaceMatcher, CombineIsEq6AndConfidenceEq7) {
  // Three test images, two places. Totals (eq. 6): (1 + 3 + 1) / 3 = 5/3 and (2 + 1 + 5) / 3 = 8/3
  // -> place 0; images 1 and 3 vote for it: confidence 2/3 (eq. 7); margin (8/3 - 5/3) / (8/3).
  const Recognition r = combineTestImages({{1, 2}, {3, 1}, {1, 5}}, 4, Distance::kJeffrey);
  EXPECT_EQ(r.place, 0);
  EXPECT_NEAR(r.total_distances[0], 5.0 / 3, 1e-12);
  EXPECT_NEAR(r.total_distances[1], 8.0 / 3, 1e-12);
  EXPECT_EQ(r.votes, (std::vector<int>{2, 1}));
  EXPECT_NEAR(r.confidence, 2.0 / 3, 1e-12);
  EXPECT_NEAR(r.margin, 3.0 / 8, 1e-12);
  EXPECT_EQ(r.space, 4);
  EXPECT_THROW(combineTestImages({}, 0, Distance::kJeffrey), std::invalid_argument);
  EXPECT_THROW(combineTestImages({{1, 2}, {1}}, 0, Distance::kJeffrey), std::invalid_argument);
}

TEST(PlaceMatcher, MostConfidentPrefersConfidenceThenMargin) {
  Recognition a, b, c;
  a.confidence = 0.8;
  a.margin = 0.1;
  b.confidence = 0.9;
  b.margin = 0.05;
  c.confidence = 0.9;
  c.margin = 0.2;
  c.space = 6;
  const std::vector<Recognition> all{a, b, c};
  EXPECT_EQ(&mostConfident(all), &all[2]);
  EXPECT_THROW(mostConfident({}), std::invalid_argument);
}

TEST(PlaceMatcher, RecognizeAllOverSpacesAndMethods) {
  PlaceIndex index(2);
  index.addPlace("a");
  index.addPlace("b");
  index.addImage(0, hist(1.0f));
  index.addImage(1, hist(0.0f));
  const auto all = recognizeAll(index, {hist(0.9f), hist(0.7f), hist(0.2f)}, {0, 2}, kAll);
  ASSERT_EQ(all.size(), kAll.size());  // space 2 has no training image: skipped
  for (const Recognition& r : all) {
    EXPECT_EQ(r.place, 0) << distanceName(r.method);
    EXPECT_NEAR(r.confidence, 2.0 / 3, 1e-12) << distanceName(r.method);
  }
}

TEST(PlaceFilter, PredictFollowsAdjacency) {
  // Chain 0 - 1 - 2. From certainty at 0 with stay 0.8 and no teleport: 0.8 stays, 0.2 moves to 1.
  PlaceFilterConfig cfg;
  cfg.stay_probability = 0.8;
  cfg.teleport_probability = 0.0;
  cfg.likelihood_sharpness = 1.0;
  PlaceFilter f({{1}, {0, 2}, {1}}, cfg);
  f.update({0.0, 10.0, 10.0});  // median - min = 10: likelihoods (1, e^-1, e^-1)
  const double e1 = std::exp(-1.0), z = 1 + 2 * e1;
  EXPECT_NEAR(f.belief()[0], 1 / z, 1e-12);
  EXPECT_NEAR(f.belief()[1], e1 / z, 1e-12);
  f.predict();
  // 0: 0.8 b0 + 0.1 b1; 1: 0.2 b0 + 0.8 b1 + 0.2 b2; 2: 0.1 b1 + 0.8 b2.
  EXPECT_NEAR(f.belief()[0], (0.8 + 0.1 * e1) / z, 1e-12);
  EXPECT_NEAR(f.belief()[1], (0.2 + 0.8 * e1 + 0.2 * e1) / z, 1e-12);
  EXPECT_NEAR(f.belief()[2], (0.1 * e1 + 0.8 * e1) / z, 1e-12);
  double s = 0;
  for (double b : f.belief()) s += b;
  EXPECT_NEAR(s, 1.0, 1e-12);
}

TEST(PlaceFilter, LikelihoodIsScaleFreeAndHandlesUntrainedPlaces) {
  PlaceFilterConfig cfg;
  cfg.likelihood_sharpness = 2.0;
  PlaceFilter f({{}, {}, {}}, cfg);
  const auto l = f.likelihood({1.0, 2.0, 3.0});  // min 1, median 2
  EXPECT_NEAR(l[0], 1.0, 1e-12);
  EXPECT_NEAR(l[1], std::exp(-2.0), 1e-12);
  EXPECT_NEAR(l[2], std::exp(-4.0), 1e-12);
  const auto l10 = f.likelihood({10.0, 20.0, 30.0});
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(l10[i], l[i], 1e-12);
  const auto inf = f.likelihood({1.0, INFINITY, 3.0});
  EXPECT_EQ(inf[1], 0.0);
  EXPECT_THROW(f.likelihood({1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(f.likelihood({1.0, NAN, 2.0}), std::invalid_argument);
  EXPECT_THROW(PlaceFilter(std::vector<std::vector<int>>{{5}}), std::invalid_argument);
}

TEST(PlaceFilter, SuccessiveImagesOutvoteOneBadImage) {
  // Two places; four images favour place 1 mildly, then one image favours place 0 strongly. The
  // filter stays with 1 where the single image would not.
  PlaceFilterConfig cfg;
  cfg.stay_probability = 0.9;
  cfg.teleport_probability = 0.0;
  cfg.likelihood_sharpness = 1.0;
  PlaceFilter f({{1}, {0}, {}}, cfg);
  for (int i = 0; i < 4; ++i) {
    f.predict();
    f.update({1.5, 1.0, 2.0});
  }
  f.predict();
  f.update({1.0, 1.3, 2.0});
  EXPECT_EQ(f.best(), 1);
}

TEST(PlaceMatcher, FastJeffreyAgreesWithTheDefinition) {
  // Random sparse histograms over 64 bins: nodeDistances' rewritten Jeffrey against eq. (3).
  std::mt19937 gen(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  auto random_hist = [&] {
    ImageHistograms h;
    h.bins = 64;
    h.spaces[2].assign(3 * 64, 0.0f);
    for (int band = 0; band < 3; ++band) {
      double s = 0;
      for (int i = 0; i < 64; ++i)
        if (u(gen) < 0.4f) s += (h.spaces[2][band * 64 + i] = u(gen));
      for (int i = 0; i < 64; ++i) h.spaces[2][band * 64 + i] /= static_cast<float>(s);
    }
    return h;
  };
  PlaceIndex index(64);
  index.addPlace("a");
  std::vector<ImageHistograms> train;
  for (int i = 0; i < 5; ++i) {
    train.push_back(random_hist());
    index.addImage(0, train.back());
  }
  const ImageHistograms test = random_hist();
  double expect = 0.0;
  for (const auto& t : train)
    expect += histogramDistance(Distance::kJeffrey, test.spaces[2].data(), t.spaces[2].data(), 64);
  expect /= train.size();
  EXPECT_NEAR(index.nodeDistances(2, Distance::kJeffrey, test)[0], expect, 1e-5);
  EXPECT_GT(expect, 0.1);
}
