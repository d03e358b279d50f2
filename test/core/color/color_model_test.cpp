#include "adaptive_perception/color/color_model.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "../refusal.h"
#include "adaptive_perception/color/color_lut.h"
#include "adaptive_perception/color/prior_learning.h"
#include "adaptive_perception/color/switching_color_filter.h"
#include "adaptive_perception/math/gaussian.h"

using namespace adaptive_perception;
using namespace adaptive_perception::color;

namespace {

ColorModelConfig twoColors() {
  ColorModelConfig c;
  c.classes = {0, 1};  // green, white
  c.min_pixels_per_color = 1;
  return c;
}

// A prior over two colours with strong cross-colour correlation (lighting scales both).
LightingPrior correlatedPrior(double green_y = 80.0, double white_y = 200.0) {
  LightingPrior p;
  p.name = "test";
  p.color_names = {"green", "white"};
  p.mean.resize(6);
  p.mean << green_y, 110, 100, white_y, 128, 128;
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(6, 6) * 4.0;
  Eigen::VectorXd lighting(6);
  lighting << 20, 2, 2, 40, 1, 1;  // a shared brightness factor
  p.cov = a * a + lighting * lighting.transpose();
  p.pixel_noise_var = {25, 9, 9};
  return p;
}

ColorObservation observe(const std::vector<int>& counts,
                         const std::vector<Eigen::Vector3d>& means) {
  ColorObservation o;
  o.counts = counts;
  o.means = means;
  o.variances.assign(counts.size(), Eigen::Vector3d(25, 9, 9));
  return o;
}

}  // namespace

TEST(ColorObservation, MeansAndVariancesOfLabelledPixels) {
  cv::Mat yuv(2, 3, CV_8UC3), labels(2, 3, CV_8UC1);
  yuv.at<cv::Vec3b>(0, 0) = {10, 100, 200};
  yuv.at<cv::Vec3b>(0, 1) = {20, 110, 210};
  yuv.at<cv::Vec3b>(0, 2) = {99, 99, 99};
  yuv.at<cv::Vec3b>(1, 0) = {200, 128, 128};
  yuv.at<cv::Vec3b>(1, 1) = {50, 50, 50};
  yuv.at<cv::Vec3b>(1, 2) = {7, 7, 7};
  labels.at<std::uint8_t>(0, 0) = 0;
  labels.at<std::uint8_t>(0, 1) = 0;
  labels.at<std::uint8_t>(0, 2) = 255;  // background: skipped
  labels.at<std::uint8_t>(1, 0) = 1;
  labels.at<std::uint8_t>(1, 1) = 4;  // cyan: not modelled here
  labels.at<std::uint8_t>(1, 2) = 255;
  const ColorObservation o = computeColorObservation(yuv, labels, twoColors());
  ASSERT_EQ(o.counts.size(), 2u);
  EXPECT_EQ(o.counts[0], 2);
  EXPECT_EQ(o.counts[1], 1);
  EXPECT_NEAR((o.means[0] - Eigen::Vector3d(15, 105, 205)).norm(), 0, 1e-12);
  EXPECT_NEAR((o.variances[0] - Eigen::Vector3d(25, 25, 25)).norm(), 0, 1e-9);
  EXPECT_NEAR((o.means[1] - Eigen::Vector3d(200, 128, 128)).norm(), 0, 1e-12);
}

// With no drift, a sequence of updates equals the batch Gaussian posterior (information form).
TEST(ColorFilter, UpdatesEqualBatchPosterior) {
  ColorModelConfig cfg = twoColors();
  cfg.drift_std_per_sqrt_s = 0.0;
  const LightingPrior prior = correlatedPrior();
  ColorFilter f(prior, cfg);
  Eigen::MatrixXd info = prior.cov.inverse();
  Eigen::VectorXd info_vec = info * prior.mean;
  math::Rng rng(3);
  for (int t = 0; t < 8; ++t) {
    const int n0 = 50 + 10 * t, n1 = t % 3 == 0 ? 0 : 30;  // white sometimes absent
    const ColorObservation o = observe({n0, n1}, {Eigen::Vector3d(70 + rng.gaussian(), 112, 99),
                                                  Eigen::Vector3d(185 + rng.gaussian(), 127, 129)});
    f.predict(0.1);
    f.update(o);
    for (int k = 0; k < 2; ++k) {
      if (o.counts[k] == 0) continue;
      for (int ch = 0; ch < 3; ++ch) {
        const int i = componentIndex(k, ch);
        const double r = prior.pixel_noise_var[ch] / o.counts[k] + cfg.observation_noise_floor_var;
        info(i, i) += 1.0 / r;
        info_vec[i] += o.means[k][ch] / r;
      }
    }
  }
  const Eigen::MatrixXd cov = info.inverse();
  EXPECT_LT((f.cov() - cov).norm(), 1e-8);
  EXPECT_LT((f.mean() - cov * info_vec).norm(), 1e-8);
}

// Observing only green moves the white estimate through the learned correlation, exactly as the
// conditional of the joint Gaussian of state and observation (the paper's footnote-1 regression).
TEST(ColorFilter, PartialObservationEqualsConditioning) {
  ColorModelConfig cfg = twoColors();
  const LightingPrior prior = correlatedPrior();
  ColorFilter f(prior, cfg);
  const ColorObservation o =
      observe({400, 0}, {Eigen::Vector3d(60, 108, 101), Eigen::Vector3d::Zero()});
  f.update(o);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(3, 6);
  h.leftCols(3).setIdentity();
  Eigen::Matrix3d r = Eigen::Matrix3d::Zero();
  for (int ch = 0; ch < 3; ++ch)
    r(ch, ch) = prior.pixel_noise_var[ch] / 400 + cfg.observation_noise_floor_var;
  Eigen::MatrixXd jc(9, 9);
  jc << prior.cov, prior.cov * h.transpose(), h * prior.cov, h * prior.cov * h.transpose() + r;
  Eigen::VectorXd jm(9);
  jm << prior.mean, h * prior.mean;
  const math::Gaussian cond = math::Gaussian(jm, jc).conditional({6, 7, 8}, o.means[0]);
  EXPECT_LT((cond.mean() - f.mean()).norm(), 1e-9);
  EXPECT_LT((cond.cov() - f.cov()).norm(), 1e-9);
  // Darker green implies darker white.
  EXPECT_LT(f.colorMean(1)[0], prior.mean[3] - 10.0);
}

// Eq. (9): the closed form equals the integral over lighting, estimated by Monte Carlo.
TEST(ColorFilter, PixelLikelihoodEqualsMonteCarloIntegral) {
  const LightingPrior prior = correlatedPrior();
  const ColorFilter f(prior, twoColors());
  const PixelClassifier cls = f.classifier();
  const math::Gaussian lighting(prior.mean, prior.cov);
  const math::Gaussian pixel_noise(Eigen::Vector3d::Zero(),
                                   Eigen::Matrix3d(prior.pixel_noise_var.asDiagonal()));
  math::Rng rng(5);
  // Near each colour (where the density is large enough for a Monte Carlo estimate to be precise).
  for (int k = 0; k < 2; ++k) {
    for (const Eigen::Vector3d& offset : {Eigen::Vector3d(5, 2, -2), Eigen::Vector3d(-15, -3, 4)}) {
      const Eigen::Vector3d c = f.colorMean(k) + offset;
      double sum = 0.0;
      const int n = 200000;
      for (int s = 0; s < n; ++s) {
        const Eigen::VectorXd theta = lighting.sample(rng);
        sum += std::exp(math::Gaussian(theta.segment<3>(3 * k), pixel_noise.cov()).logDensity(c));
      }
      const double mc = sum / n, closed = std::exp(cls.logLikelihood(c, k));
      EXPECT_NEAR(mc / closed, 1.0, 0.03) << "colour " << k;
    }
  }
  EXPECT_EQ(cls.classify(Eigen::Vector3d(82, 110, 100)), 0);
  EXPECT_EQ(cls.classify(Eigen::Vector3d(198, 128, 128)), 1);
  EXPECT_EQ(cls.classify(Eigen::Vector3d(30, 240, 20)), 255);  // far from both: unknown
}

TEST(LightingPrior, YamlRoundTripAndErrors) {
  const LightingPrior p = correlatedPrior();
  const std::string path = ::testing::TempDir() + "/prior_test.yaml";
  p.saveYaml(path);
  const LightingPrior q = LightingPrior::loadYaml(path);
  EXPECT_EQ(q.color_names, p.color_names);
  EXPECT_LT((q.mean - p.mean).norm(), 1e-9);
  EXPECT_LT((q.cov - p.cov).norm(), 1e-6);
  const LightingPrior ind = p.independent();
  EXPECT_EQ((ind.cov.block<3, 3>(0, 3)).norm(), 0.0);
  EXPECT_EQ(((ind.cov.block<3, 3>(3, 3)) - (p.cov.block<3, 3>(3, 3))).norm(), 0.0);
  {
    FILE* f = std::fopen(path.c_str(), "w");
    std::fputs("colors: [green]\nmean: [1, 2]\ncov: [[1]]\npixel_noise_var: [1, 1, 1]\n", f);
    std::fclose(f);
  }
  try {
    LightingPrior::loadYaml(path);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("mean"), std::string::npos) << e.what();
  }
  EXPECT_THROW(LightingPrior::loadYaml("/nonexistent.yaml"), std::runtime_error);
}

// Prior learning recovers the hyperparameters of synthetic environments.
TEST(PriorLearning, RecoversKnownHyperparameters) {
  const LightingPrior truth = correlatedPrior();
  ColorModelConfig cfg = twoColors();
  const math::Gaussian env_dist(truth.mean, truth.cov);
  math::Rng rng(7);
  std::vector<LightingDataSet> sets;
  for (int j = 0; j < 400; ++j) {
    const Eigen::VectorXd theta = env_dist.sample(rng);
    LightingDataSet s;
    for (int t = 0; t < 10; ++t) {
      ColorObservation o;
      o.counts = {200, t % 4 == 0 ? 0 : 50};
      o.means.resize(2);
      o.variances.assign(2, truth.pixel_noise_var);
      for (int k = 0; k < 2; ++k)
        for (int ch = 0; ch < 3; ++ch) {
          const double r = observationVariance(cfg, truth.pixel_noise_var, o.counts[k], ch);
          o.means[k][ch] = theta[3 * k + ch] + rng.gaussian(0.0, std::sqrt(r));
        }
      s.frames.push_back(o);
    }
    sets.push_back(s);
  }
  PriorLearningConfig lc;
  lc.hyper_prior_std = 1.0;
  const LightingPrior learnt = learnPrior(sets, cfg, lc, "learnt");
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(learnt.mean[i], truth.mean[i], 4.0 * std::sqrt(truth.cov(i, i) / 400)) << i;
    EXPECT_NEAR(learnt.cov(i, i), truth.cov(i, i), 0.2 * truth.cov(i, i) + 2.0) << i;
  }
  // The cross-colour correlation of the brightness is recovered.
  const double corr = learnt.cov(0, 3) / std::sqrt(learnt.cov(0, 0) * learnt.cov(3, 3));
  const double corr_true = truth.cov(0, 3) / std::sqrt(truth.cov(0, 0) * truth.cov(3, 3));
  EXPECT_NEAR(corr, corr_true, 0.08);
  EXPECT_NEAR(learnt.pixel_noise_var[0], 25.0, 1e-9);
}

TEST(PriorLearning, KMeansSeparatesDarkFromBright) {
  Eigen::MatrixXd x(8, 2);
  x << 200, 210, 40, 50, 205, 215, 45, 52, 198, 207, 38, 49, 202, 212, 41, 51;
  const std::vector<int> a = kMeans(x, 2, 1);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(a[i], i % 2 == 0 ? 1 : 0) << i;  // cluster 0 = darkest
}

// Mode selection picks the prior that explains the image: dark images select the dark mode.
TEST(SwitchingColorFilter, SelectsTheModeThatExplainsTheImage) {
  const LightingPrior dark = [] {
    LightingPrior p = correlatedPrior(40.0, 110.0);
    p.name = "dark";
    return p;
  }();
  const LightingPrior bright = [] {
    LightingPrior p = correlatedPrior(90.0, 220.0);
    p.name = "bright";
    return p;
  }();
  for (auto mixing : {ModeMixing::kBestMode, ModeMixing::kImm}) {
    SwitchingFilterConfig sc;
    sc.mixing = mixing;
    SwitchingColorFilter f({dark, bright}, twoColors(), sc);
    auto frame = [](double g, double w) {
      return observe({300, 100}, {Eigen::Vector3d(g, 110, 100), Eigen::Vector3d(w, 128, 128)});
    };
    for (int t = 0; t < 5; ++t) {
      f.predict(0.25);
      f.update(frame(92, 215));
    }
    EXPECT_EQ(f.modeName(f.activeMode()), "bright");
    // Best-mode keeps the unused mode at its own estimate, so the evidence separates them sharply;
    // IMM mixes the modes every step and gives softer probabilities: there the MAP mode is what
    // counts.
    if (mixing == ModeMixing::kBestMode) {
      EXPECT_GT(f.modeProbabilities()[1], 0.9);
    }
    // The light goes off.
    f.predict(0.25);
    f.update(frame(42, 105));
    EXPECT_EQ(f.modeName(f.activeMode()), "dark");
    f.predict(0.25);
    f.update(frame(43, 106));
    EXPECT_EQ(f.modeName(f.activeMode()), "dark");
    if (mixing == ModeMixing::kBestMode) {
      EXPECT_GT(f.modeProbabilities()[0], 0.9);
    }
  }
}

// The table gives the direct classification at every cell centre, and almost everywhere else.
TEST(ColorLut, AgreesWithDirectClassification) {
  const ColorFilter f(correlatedPrior(), twoColors());
  const PixelClassifier cls = f.classifier();
  ColorLut lut;
  lut.build(cls);
  math::Rng rng(2);
  int agree = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const auto y = static_cast<std::uint8_t>(rng.uniformInt(0, 255));
    const auto u = static_cast<std::uint8_t>(rng.uniformInt(0, 255));
    const auto v = static_cast<std::uint8_t>(rng.uniformInt(0, 255));
    EXPECT_EQ(lut.lookup(y, u, v), cls.classify(ColorLut::cellCentre(y, u, v)));
    agree += lut.lookup(y, u, v) == cls.classify(Eigen::Vector3d(y, u, v));
  }
  EXPECT_GT(agree, 0.99 * n);
  // Near the colours themselves (where pixels are), agreement is also high.
  const Eigen::Vector3d g = f.colorMean(0);
  int near_agree = 0;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d c =
        g + Eigen::Vector3d{rng.gaussian(0, 25), rng.gaussian(0, 6), rng.gaussian(0, 6)};
    c = c.cwiseMax(0).cwiseMin(255).array().round();
    near_agree += lut.lookup(c[0], c[1], c[2]) == cls.classify(c);
  }
  EXPECT_GT(near_agree, 0.97 * n);
  // UYVY and per-pixel paths agree.
  cv::Mat uyvy(4, 4, CV_8UC2), labels_uyvy, labels_yuv;
  cv::randu(uyvy, 0, 255);
  cv::Mat yuv(4, 4, CV_8UC3);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; c += 2) {
      const auto p = uyvy.ptr<std::uint8_t>(r) + 2 * c;
      yuv.at<cv::Vec3b>(r, c) = {p[1], p[0], p[2]};
      yuv.at<cv::Vec3b>(r, c + 1) = {p[3], p[0], p[2]};
    }
  lut.classifyUyvy(uyvy, &labels_uyvy);
  lut.classifyYuv(yuv, &labels_yuv);
  EXPECT_EQ(cv::norm(labels_uyvy, labels_yuv, cv::NORM_INF), 0.0);
}

TEST(ColorLutCache, RebuildsOnlyOnNoticeableChange) {
  ColorFilter f(correlatedPrior(), twoColors());
  ColorLutCache cache(0.2);
  EXPECT_TRUE(cache.update(f.classifier()));
  EXPECT_FALSE(cache.update(f.classifier()));
  f.predict(0.01);  // tiny covariance change
  EXPECT_FALSE(cache.update(f.classifier()));
  f.update(observe({500, 500}, {Eigen::Vector3d(40, 100, 110), Eigen::Vector3d(120, 128, 128)}));
  EXPECT_TRUE(cache.update(f.classifier()));
  EXPECT_EQ(cache.rebuilds(), 2);
}

TEST(ColorModelConfig, RejectsBadValuesByName) {
  ColorModelConfig c;
  c.classes = {0, 0};
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c.classes = {0, 9};
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c = ColorModelConfig();
  c.drift_std_per_sqrt_s = -1;
  EXPECT_TRUE(test_support::refusedNaming([&] { c.validate(); }, "drift_std_per_sqrt_s"));
}

// The shipped priors (config/color_priors, made by scripts/learn_color_priors.sh) load and validate
// against the default model; "all" is learnt from the union of the data sets the dark and bright
// groups partition, so its mean lies between theirs in every coordinate.
TEST(ShippedPriors, LoadValidateAndAllLiesBetweenDarkAndBright) {
  const std::string dir = std::string(AP_SOURCE_DIR) + "/config/color_priors/";
  const color::ColorModelConfig config;
  std::map<std::string, color::LightingPrior> priors;
  for (const char* name : {"dark", "bright", "all"}) {
    priors[name] = color::LightingPrior::loadYaml(dir + name + ".yaml");
    EXPECT_EQ(priors[name].name, name);
    EXPECT_NO_THROW(priors[name].validate(config)) << name;
  }
  const Eigen::VectorXd& dark = priors["dark"].mean;
  const Eigen::VectorXd& bright = priors["bright"].mean;
  const Eigen::VectorXd& all = priors["all"].mean;
  ASSERT_EQ(all.size(), dark.size());
  for (Eigen::Index i = 0; i < all.size(); ++i) {
    EXPECT_GE(all[i], std::min(dark[i], bright[i]) - 1e-9) << "coordinate " << i;
    EXPECT_LE(all[i], std::max(dark[i], bright[i]) + 1e-9) << "coordinate " << i;
  }
  EXPECT_EQ(priors["all"].color_names, priors["dark"].color_names);
}
