// adaptPriorsToImage against the Kalman update worked by hand: a prior in which the carpet's and a
// landmark's luma vary together moves the landmark with the carpet the image shows; a venue far
// outside the prior widens it until the image's innovation is typical (its squared Mahalanobis
// distance equals its dimension, by hand); the pixel noise becomes the carpet's texture where that
// is larger; bad input is refused.
#include "adaptive_perception/color/image_adapted_prior.h"

#include <gtest/gtest.h>

#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::color {
namespace {

constexpr double kPriorVar = 100.0, kCross = 80.0;

LightingPrior correlatedPrior(const ColorModelConfig& model) {
  LightingPrior p;
  p.name = "test";
  for (const std::uint8_t c : model.classes) p.color_names.push_back(world::colorClassName(c));
  p.mean = Eigen::VectorXd::Constant(model.dim(), 128.0);
  p.cov = Eigen::MatrixXd::Identity(model.dim(), model.dim()) * kPriorVar;
  const int gy = componentIndex(model.colorIndex(world::kGreen), 0);
  const int py = componentIndex(model.colorIndex(world::kPink), 0);
  p.cov(gy, py) = p.cov(py, gy) = kCross;
  p.pixel_noise_var = {25.0, 9.0, 9.0};
  return p;
}

// 100 x 100: the top 40 rows background, the bottom 60 carpet (luma alternating carpet_y - 10 /
// carpet_y + 10 along each row: variance 100; U 126, V 127) with rows 60-61 line paint
// (white_y, 128, 128).
void scene(int carpet_y, int white_y, cv::Mat* yuv, FieldSegmentation* seg) {
  *yuv = cv::Mat(100, 100, CV_8UC3, cv::Scalar(150, 128, 128));
  seg->labels = cv::Mat(100, 100, CV_8UC1, cv::Scalar(world::kBackground));
  for (int r = 40; r < 100; ++r)
    for (int c = 0; c < 100; ++c) {
      const bool line = r == 60 || r == 61;
      yuv->at<cv::Vec3b>(r, c) = line ? cv::Vec3b(white_y, 128, 128)
                                      : cv::Vec3b(c % 2 ? carpet_y + 10 : carpet_y - 10, 126, 127);
      seg->labels.at<std::uint8_t>(r, c) = line ? world::kWhite : world::kGreen;
    }
}

ColorModelConfig testModel() {
  ColorModelConfig model;
  model.observation_noise = ObservationNoise::kPixelNoiseOverCount;
  model.observation_noise_floor_var = 4.0;
  return model;
}

// Per observed component: (innovation, observation noise) for the scene: green 5800 pixels, white
// 200, noise nu / n + 4 with the prior's nu (25, 9, 9).
struct Observed {
  double y, r;
};
std::vector<Observed> observed(int carpet_y, int white_y) {
  const double rg = 1.0 / 5800, rw = 1.0 / 200;
  return {{carpet_y - 128.0, 25 * rg + 4}, {-2.0, 9 * rg + 4}, {-1.0, 9 * rg + 4},
          {white_y - 128.0, 25 * rw + 4},  {0.0, 9 * rw + 4},  {0.0, 9 * rw + 4}};
}

TEST(ImageAdaptedPrior, KalmanUpdateByHandCarriesTheCarpetToTheLandmark) {
  const ColorModelConfig model = testModel();
  const LightingPrior prior = correlatedPrior(model);
  cv::Mat yuv;
  FieldSegmentation seg;
  scene(125, 135, &yuv, &seg);  // within the prior: d2 = 9/104 + ... < 6, no widening
  const auto adapted = adaptPriorsToImage({prior}, yuv, seg, model);
  ASSERT_EQ(adapted.size(), 1u);
  const LightingPrior& a = adapted[0];
  EXPECT_EQ(a.name, "test");
  const int g = model.colorIndex(world::kGreen), w = model.colorIndex(world::kWhite),
            p = model.colorIndex(world::kPink), y = model.colorIndex(world::kYellow);
  // Green luma: scalar Kalman gain (the observed components are uncorrelated in the prior).
  const auto obs = observed(125, 135);
  const double gain = kPriorVar / (kPriorVar + obs[0].r);
  EXPECT_NEAR(a.mean[componentIndex(g, 0)], 128.0 + gain * obs[0].y, 1e-9);
  // Pink luma is not observed; it moves by cov(p, g) / (var(g) + r) times the green innovation.
  EXPECT_NEAR(a.mean[componentIndex(p, 0)], 128.0 + kCross / (kPriorVar + obs[0].r) * obs[0].y,
              1e-9);
  EXPECT_NEAR(a.cov(componentIndex(p, 0), componentIndex(p, 0)),
              kPriorVar - kCross * kCross / (kPriorVar + obs[0].r), 1e-9);
  EXPECT_NEAR(a.mean[componentIndex(w, 0)], 128.0 + kPriorVar / (kPriorVar + obs[3].r) * obs[3].y,
              1e-9);
  // Yellow: neither observed nor correlated: unchanged, and the prior was not widened.
  EXPECT_DOUBLE_EQ(a.mean[componentIndex(y, 0)], 128.0);
  EXPECT_DOUBLE_EQ(a.cov(componentIndex(y, 0), componentIndex(y, 0)), kPriorVar);
  // nu: the carpet's luma variance (100) is above the prior's 25; its chroma has none.
  EXPECT_NEAR(a.pixel_noise_var[0], 100.0, 1e-9);
  EXPECT_DOUBLE_EQ(a.pixel_noise_var[1], 9.0);
  EXPECT_DOUBLE_EQ(a.pixel_noise_var[2], 9.0);
}

TEST(ImageAdaptedPrior, AVenueFarOutsideThePriorWidensItUntilTheImageIsTypical) {
  const ColorModelConfig model = testModel();
  const LightingPrior prior = correlatedPrior(model);
  cv::Mat yuv;
  FieldSegmentation seg;
  scene(60, 200, &yuv, &seg);  // carpet 68 levels darker, paint 72 brighter: d2 near 94 > 6
  const auto obs = observed(60, 200);
  const auto d2 = [&](double s) {
    double sum = 0.0;
    for (const Observed& o : obs) sum += o.y * o.y / (s * kPriorVar + o.r);
    return sum;
  };
  ASSERT_GT(d2(1.0), 6.0);
  const LightingPrior a = adaptPriorsToImage({prior}, yuv, seg, model)[0];
  const int g = model.colorIndex(world::kGreen), p = model.colorIndex(world::kPink),
            y = model.colorIndex(world::kYellow);
  // The widening, read off the unobserved, uncorrelated yellow: the image is a typical draw.
  const double s = a.cov(componentIndex(y, 0), componentIndex(y, 0)) / kPriorVar;
  EXPECT_GT(s, 1.0);
  EXPECT_NEAR(d2(s), 6.0, 1e-6);
  EXPECT_NEAR(priorWidening(prior, computeColorObservation(yuv, seg.labels, model), model), s,
              1e-9 * s);
  // The carpet lands on the image's (gain near 1), and pink follows by the same regression.
  const double sgg = s * kPriorVar, spg = s * kCross;
  EXPECT_NEAR(a.mean[componentIndex(g, 0)], 128.0 + sgg / (sgg + obs[0].r) * obs[0].y, 1e-9);
  EXPECT_NEAR(a.mean[componentIndex(g, 0)], 60.0, 0.5);
  EXPECT_NEAR(a.mean[componentIndex(p, 0)], 128.0 + spg / (sgg + obs[0].r) * obs[0].y, 1e-9);
}

TEST(ImageAdaptedPrior, NothingLabelledLeavesThePriorAndBadInputIsRefused) {
  const ColorModelConfig model;
  const LightingPrior prior = correlatedPrior(model);
  cv::Mat yuv;
  FieldSegmentation seg;
  scene(60, 200, &yuv, &seg);
  FieldSegmentation none;
  none.labels = cv::Mat(100, 100, CV_8UC1, cv::Scalar(world::kBackground));
  const auto same = adaptPriorsToImage({prior}, yuv, none, model);
  EXPECT_TRUE(same[0].mean.isApprox(prior.mean));
  EXPECT_TRUE(same[0].cov.isApprox(prior.cov));
  EXPECT_EQ(same[0].pixel_noise_var, prior.pixel_noise_var);
  FieldSegmentation small;
  small.labels = cv::Mat(10, 10, CV_8UC1, cv::Scalar(world::kGreen));
  EXPECT_THROW(adaptPriorsToImage({prior}, yuv, small, model), std::invalid_argument);
  LightingPrior wrong = prior;
  wrong.mean.resize(3);
  EXPECT_THROW(adaptPriorsToImage({wrong}, yuv, seg, model), std::exception);
}

}  // namespace
}  // namespace adaptive_perception::color
