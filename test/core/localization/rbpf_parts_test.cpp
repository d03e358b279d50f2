// The parts RbpfLocalizer is built from, each against its header's contract: the pose cluster
// (worked by hand), the pose search's draw (a closed form), its uniform pool, and the state
// machines of the global search and the relocalization check. The filter as a whole is tested in
// rbpf_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "adaptive_perception/localization/global_localization.h"
#include "adaptive_perception/localization/pose_cluster.h"
#include "adaptive_perception/localization/pose_search.h"
#include "adaptive_perception/localization/rbpf_localizer.h"
#include "adaptive_perception/localization/relocalization_monitor.h"

using namespace adaptive_perception;
using namespace adaptive_perception::localization;

namespace {
// Two hypotheses: A (three particles near (1.1, 1.03), weight 0.6) and B (two at (-1, -1) with
// headings either side of pi, weight 0.4).
std::vector<math::SE2> twoHypotheses() {
  return {math::SE2(1.0, 1.0, 0.1), math::SE2(1.2, 1.0, -0.1), math::SE2(1.1, 1.1, 0.0),
          math::SE2(-1.0, -1.0, 3.1), math::SE2(-1.0, -1.0, -3.1)};
}
const std::vector<double> kWeights = {0.2, 0.2, 0.2, 0.2, 0.2};

std::shared_ptr<const ImageLikelihood> fieldLikelihood() {
  return std::make_shared<const ImageLikelihood>(
      world::FieldMap(), world::PinholeCamera::aiboErs7(), RbpfConfig::rbpfModelConfig(),
      ImageLikelihoodConfig());
}

cv::Mat greyImage() {
  const world::PinholeCamera cam = world::PinholeCamera::aiboErs7();
  return cv::Mat(cam.height_px, cam.width_px, CV_8UC3, cv::Scalar(120, 128, 128));
}

// The head's camera 0.3 m above the ground, looking ahead and 0.4 rad down.
/// The filter the localizer gives each particle, on the one shipped prior `name`
/// (config/color_priors/<name>.yaml).
color::SwitchingColorFilter lightingOf(const std::string& name) {
  return color::SwitchingColorFilter(
      {color::LightingPrior::loadYaml(std::string(AP_SOURCE_DIR) + "/config/color_priors/" + name +
                                      ".yaml")},
      RbpfConfig::rbpfModelConfig(), color::SwitchingFilterConfig());
}

Eigen::Isometry3d cameraOnRobot() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(0.1, 0.0, 0.3);
  // Optical frame: z forward, x right, y down; tilted down by 0.4 rad.
  Eigen::Matrix3d optical;
  optical << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  t.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()).toRotationMatrix() * optical;
  return t;
}
}  // namespace

// By hand: A's mean is (1.1, 1.0333, 0) with var(x) = (0.01 + 0.01 + 0) / 3 and var(y) =
// (0.0011 + 0.0011 + 0.0044) / 3; it holds 0.6 of the weight. B's mean heading is pi (not 0, the
// arithmetic mean of 3.1 and -3.1).
TEST(PoseCluster, TheEstimateIsTheHeavierHypothesisMean) {
  const std::vector<math::SE2> poses = twoHypotheses();
  const PoseEstimate e = estimatePose(poses, kWeights);
  EXPECT_NEAR(e.pose.x_m, 1.1, 1e-12);
  EXPECT_NEAR(e.pose.y_m, 3.1 / 3.0, 1e-12);
  EXPECT_NEAR(e.pose.yaw_rad, 0.0, 1e-12);
  EXPECT_NEAR(e.cluster_weight, 0.6, 1e-12);
  EXPECT_NEAR(e.covariance(0, 0), 0.02 / 3.0, 1e-12);
  const double dy = 1.0 - 3.1 / 3.0;
  EXPECT_NEAR(e.covariance(1, 1), (2 * dy * dy + (0.1 + dy) * (0.1 + dy)) / 3.0, 1e-12);
  EXPECT_NEAR(e.covariance(2, 2), 0.02 / 3.0, 1e-12);
  // The spread of all five: x and y each have mean (3.3 - 2) / 5 = 0.26 over equal weights.
  double sxx = 0.0, syy = 0.0;
  for (const math::SE2& p : poses) {
    sxx += (p.x_m - 0.26) * (p.x_m - 0.26) / 5.0;
    syy += (p.y_m - 3.1 / 5.0 + 2.0 / 5.0) * (p.y_m - 3.1 / 5.0 + 2.0 / 5.0) / 5.0;
  }
  EXPECT_NEAR(e.spread_m, std::sqrt(sxx + syy), 1e-12);

  const std::vector<std::size_t> b = {3, 4};
  const math::SE2 mb = weightedMean(poses, kWeights, b);
  EXPECT_NEAR(std::fabs(math::angleDiff(mb.yaw_rad, math::kPi)), 0.0, 1e-12);
  EXPECT_NEAR(mb.x_m, -1.0, 1e-12);
  // About its circular mean the headings lie 0.0416 rad either side.
  EXPECT_NEAR(covarianceAbout(poses, kWeights, b, mb)(2, 2), std::pow(math::kPi - 3.1, 2), 1e-12);
}

TEST(PoseCluster, WeightsNeedNotBeNormalisedAndNoWeightGivesTheOrigin) {
  std::vector<double> w = kWeights;
  for (double& x : w) x *= 7.0;
  const PoseEstimate a = estimatePose(twoHypotheses(), kWeights);
  const PoseEstimate b = estimatePose(twoHypotheses(), w);
  EXPECT_NEAR(a.pose.x_m, b.pose.x_m, 1e-12);
  EXPECT_NEAR(a.covariance(0, 0), b.covariance(0, 0), 1e-12);
  const math::SE2 none = weightedMean(twoHypotheses(), std::vector<double>(5, 0.0), {0, 1});
  EXPECT_EQ(none.x_m, 0.0);
  EXPECT_EQ(none.y_m, 0.0);
}

TEST(Se2, PointMirrorIsAnInvolutionThroughTheOrigin) {
  const math::SE2 p(1.5, -0.5, 3.0);
  const math::SE2 m = math::pointMirror(p);
  EXPECT_DOUBLE_EQ(m.x_m, -1.5);
  EXPECT_DOUBLE_EQ(m.y_m, 0.5);
  EXPECT_NEAR(m.yaw_rad, 3.0 - math::kPi, 1e-15);
  const math::SE2 back = math::pointMirror(m);
  EXPECT_NEAR(math::angleDiff(back.yaw_rad, p.yaw_rad), 0.0, 1e-15);
}

// ll_i = -i: flattened by lambda the weights are geometric with ratio r = exp(-lambda), whose
// effective sample size is (1 + r) / (1 - r). The draw keeps count / 2 = 50 effective, so r =
// 49 / 51 and the drawn indices have the geometric mean r / (1 - r) = 24.5 (systematic resampling
// draws close to it). Flat scores: every pose once.
TEST(PoseSearch, DrawFlattensTheScoresToKeepHalfTheDrawEffective) {
  PoseSearch search(fieldLikelihood(), PoseSearchConfig(), 1);
  const std::size_t n = 2000;
  std::vector<double> ll(n);
  for (std::size_t i = 0; i < n; ++i) ll[i] = -static_cast<double>(i);
  math::Rng rng(3);
  const std::vector<std::size_t> idx = search.draw(ll, n, 100, rng);
  ASSERT_EQ(idx.size(), 100u);
  const double mean = std::accumulate(idx.begin(), idx.end(), 0.0) / idx.size();
  EXPECT_NEAR(mean, 24.5, 1.0);
  // Unflattened (lambda 1) nearly every draw would be index 0 or 1.
  EXPECT_GT(std::count_if(idx.begin(), idx.end(), [](std::size_t i) { return i > 10; }), 50);

  const std::vector<double> flat(100, -3.0);
  std::vector<std::size_t> once = search.draw(flat, 100, 100, rng);
  std::sort(once.begin(), once.end());
  for (std::size_t i = 0; i < once.size(); ++i) EXPECT_EQ(once[i], i);
}

TEST(PoseSearch, UniformPoolIsMirroredPairsWhereARobotCanStandForAnyThreadCount) {
  const auto likelihood = fieldLikelihood();
  const PoseSearchConfig config;
  PoseSearch one(likelihood, config, 1), two(likelihood, config, 2);
  std::vector<math::SE2> a(301), b(301);
  one.fillUniform(&a, a.size(), 42);
  two.fillUniform(&b, b.size(), 42);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x_m, b[i].x_m);
    EXPECT_EQ(a[i].yaw_rad, b[i].yaw_rad);
    EXPECT_TRUE(likelihood->map().isFree(a[i].x_m, a[i].y_m, config.free_space_margin_m))
        << "pose " << i;
    if (i % 2 == 1) {
      const math::SE2 m = math::pointMirror(a[i - 1]);
      EXPECT_EQ(a[i].x_m, m.x_m);
      EXPECT_EQ(a[i].y_m, m.y_m);
      EXPECT_EQ(a[i].yaw_rad, m.yaw_rad);
    }
  }
  PoseSearchConfig bad;
  bad.refine_sigma_m = -1.0;
  EXPECT_THROW(PoseSearch(likelihood, bad, 1), std::invalid_argument);
}

// start -> search_frames images searching (a draw of `count` poses each) -> confirming until
// confirm_frames -> a contest of the pool against the particles over the window's images.
TEST(GlobalLocalization, SearchesThenConfirmsThenHandsOverAContest) {
  PoseSearch search(fieldLikelihood(), PoseSearchConfig(), 2);
  GlobalLocalizationConfig config;
  config.pool_size = 200;
  config.search_frames = 2;
  config.confirm_frames = 4;
  config.refine_candidates = 5;
  GlobalLocalization global(config);
  EXPECT_FALSE(global.searching());
  global.start();
  EXPECT_TRUE(global.searching());
  const color::SwitchingColorFilter lighting = lightingOf("bright");
  const cv::Mat yuv = greyImage();
  const Eigen::Isometry3d cam = cameraOnRobot();
  const math::SE2 step(0.05, 0.0, 0.02);
  math::Rng rng(1);
  auto first = global.searchImage(&search, step, yuv, lighting, cam, 7, 30, rng);
  EXPECT_FALSE(first.committed);
  EXPECT_EQ(first.poses.size(), 30u);
  EXPECT_TRUE(global.searching());
  auto second = global.searchImage(&search, step, yuv, lighting, cam, 8, 30, rng);
  EXPECT_TRUE(second.committed);
  EXPECT_FALSE(global.searching());
  EXPECT_TRUE(global.confirming());
  const std::vector<math::SE2> particles(second.poses.begin(), second.poses.begin() + 10);
  EXPECT_FALSE(global.confirmImage(&search, step, yuv, lighting, cam, particles).has_value());
  const auto contest = global.confirmImage(&search, step, yuv, lighting, cam, particles);
  ASSERT_TRUE(contest.has_value());
  EXPECT_FALSE(global.confirming());
  EXPECT_EQ(contest->candidates, 200u);
  ASSERT_EQ(contest->poses.size(), 210u);
  ASSERT_EQ(contest->log_likelihoods.size(), 210u);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    EXPECT_EQ(contest->poses[200 + i].x_m, particles[i].x_m);
    // Each particle pose is scored over the window's four images.
    EXPECT_DOUBLE_EQ(contest->log_likelihoods[200 + i], search.windowLogLikelihood(particles[i]));
  }

  config.confirm_frames = config.search_frames;  // no second draw
  GlobalLocalization once(config);
  once.start();
  once.searchImage(&search, step, yuv, lighting, cam, 7, 30, rng);
  EXPECT_TRUE(once.searchImage(&search, step, yuv, lighting, cam, 8, 30, rng).committed);
  EXPECT_FALSE(once.confirming());
  config.pool_size = 0;  // off
  GlobalLocalization off(config);
  off.start();
  EXPECT_FALSE(off.searching());
  config.search_frames = 0;
  EXPECT_THROW(GlobalLocalization{config}, std::invalid_argument);
}

// A first image with a goal's proposals: a pool of goal_pool_size poses (here all proposals, so
// every drawn pose is one of them) scored on the goal_pixel_stride grid, and no second draw; the
// same search without proposals is the uniform one, with its second draw.
TEST(GlobalLocalization, AGoalsProposalsMakeTheirOwnPool) {
  PoseSearch search(fieldLikelihood(), PoseSearchConfig(), 2);
  const cv::Mat yuv = greyImage();
  const Eigen::Isometry3d cam = cameraOnRobot();
  EXPECT_EQ(search.coarseImage(yuv, cam).stride, PoseSearchConfig().pixel_stride);
  EXPECT_EQ(search.coarseImage(yuv, cam, 3).stride, 3);
  EXPECT_GT(search.coarseImage(yuv, cam, 3).pixels.size(),
            3 * search.coarseImage(yuv, cam).pixels.size());
  GlobalLocalizationConfig config;
  config.pool_size = 200;
  config.goal_pool_size = 10;
  config.search_frames = 2;
  config.confirm_frames = 4;
  config.refine_candidates = 0;
  std::vector<math::SE2> proposals;
  for (int k = 0; k < 5; ++k) {
    proposals.emplace_back(-2.0 + 0.1 * k, 1.0, 0.3 * k);
    proposals.push_back(math::pointMirror(proposals.back()));
  }
  const color::SwitchingColorFilter lighting = lightingOf("bright");
  math::Rng rng(3);
  GlobalLocalization goal(config);
  goal.start();
  EXPECT_TRUE(goal.poolPending());
  const auto first =
      goal.searchImage(&search, math::SE2(), yuv, lighting, cam, 7, 40, rng, proposals);
  EXPECT_FALSE(goal.poolPending());
  // The search's window holds the image on the goal's grid, not on the search's own.
  PoseSearch on_goal_grid(fieldLikelihood(), PoseSearchConfig(), 1), on_own_grid = on_goal_grid;
  on_goal_grid.pushWindow(math::SE2(), on_goal_grid.coarseImage(yuv, cam, config.goal_pixel_stride),
                          lighting, cam, true);
  on_own_grid.pushWindow(math::SE2(), on_own_grid.coarseImage(yuv, cam), lighting, cam, true);
  const math::SE2 probe(-1.0, 0.5, 0.2);
  EXPECT_DOUBLE_EQ(search.windowLogLikelihood(probe), on_goal_grid.windowLogLikelihood(probe));
  EXPECT_NE(search.windowLogLikelihood(probe), on_own_grid.windowLogLikelihood(probe));
  ASSERT_EQ(first.poses.size(), 40u);
  for (const math::SE2& p : first.poses) {
    const bool proposed = std::any_of(proposals.begin(), proposals.end(), [&](const math::SE2& q) {
      return q.x_m == p.x_m && q.y_m == p.y_m && q.yaw_rad == p.yaw_rad;
    });
    EXPECT_TRUE(proposed) << p.x_m << " " << p.y_m;
  }
  EXPECT_TRUE(goal.searchImage(&search, math::SE2(), yuv, lighting, cam, 8, 40, rng).committed);
  EXPECT_FALSE(goal.confirming());  // a goal's pool has no second draw
  GlobalLocalization uniform(config);
  uniform.start();
  uniform.searchImage(&search, math::SE2(), yuv, lighting, cam, 7, 40, rng);
  EXPECT_TRUE(uniform.searchImage(&search, math::SE2(), yuv, lighting, cam, 8, 40, rng).committed);
  EXPECT_TRUE(uniform.confirming());
  config.goal_pixel_stride = 0;
  EXPECT_THROW(GlobalLocalization{config}, std::invalid_argument);
}

// The image's own background colours (ImageLikelihoodConfig::background_from_image): a histogram
// of the marked pixels in cubes of 16 levels, mixed with the uniform density over the YUV cube.
// By hand: 600 pixels of one colour marked, weight w = 0.1: that colour's cube has density
// w / 256^3 + (1 - w) / 16^3, every other cube w / 256^3.
TEST(BackgroundDensity, IsTheMarkedColoursHistogramMixedWithTheUniformDensity) {
  cv::Mat yuv(30, 40, CV_8UC3, cv::Scalar(60, 100, 110));
  yuv(cv::Rect(0, 0, 40, 15)).setTo(cv::Scalar(200, 120, 130));
  cv::Mat mask = cv::Mat::zeros(30, 40, CV_8UC1);
  mask(cv::Rect(0, 0, 40, 15)).setTo(255);
  const double w = 0.1, uniform = 1.0 / (256.0 * 256.0 * 256.0);
  const BackgroundDensity d(yuv, mask, w);
  EXPECT_NEAR(d.logDensity({200, 120, 130}), std::log(w * uniform + (1 - w) / 4096.0), 1e-6);
  // Another colour of the same cube (levels 192-207, 112-127, 128-143), and one of another cube.
  EXPECT_NEAR(d.logDensity({207, 112, 143}), std::log(w * uniform + (1 - w) / 4096.0), 1e-6);
  EXPECT_NEAR(d.logDensity({60, 100, 110}), std::log(w * uniform), 1e-6);
  // Fewer than kMinPixels marked: the uniform density.
  cv::Mat few = cv::Mat::zeros(30, 40, CV_8UC1);
  few(cv::Rect(0, 0, 40, 5)).setTo(255);  // 200 pixels
  EXPECT_NEAR(BackgroundDensity(yuv, few, w).logDensity({200, 120, 130}), std::log(uniform), 1e-9);
  EXPECT_THROW(BackgroundDensity(yuv, cv::Mat::zeros(10, 10, CV_8UC1), w), std::invalid_argument);
  EXPECT_THROW(BackgroundDensity(yuv, mask, 0.0), std::invalid_argument);
}

// Strides are given for an image reference_width_px wide: a camera three times as wide samples
// every third pixel as far apart, the goal search's grid included.
TEST(RbpfConfig, ForCameraScalesEveryStrideToTheCamerasWidth) {
  RbpfConfig config;
  world::PinholeCamera wide;
  wide.width_px = 3 * config.likelihood.reference_width_px;
  wide.height_px = 2 * config.likelihood.reference_width_px;
  const RbpfConfig c = config.forCamera(wide);
  EXPECT_EQ(c.likelihood.pixel_stride, 3 * config.likelihood.pixel_stride);
  EXPECT_EQ(c.search.pixel_stride, 3 * config.search.pixel_stride);
  EXPECT_EQ(c.global.goal_pixel_stride, 3 * config.global.goal_pixel_stride);
}

// Interval 1 s at 4 images a second: the check starts on the 4th image, scores `frames` images and
// hands over its contest, with the particles' poses of its first image; then the interval starts
// again.
TEST(RelocalizationMonitor, ChecksEveryIntervalOverTheSearchsFrames) {
  PoseSearch search(fieldLikelihood(), PoseSearchConfig(), 1);
  RelocalizationConfig config;
  config.pool_size = 50;
  RelocalizationMonitor monitor(config);
  const color::SwitchingColorFilter lighting = lightingOf("dark");
  const cv::Mat yuv = greyImage();
  const Eigen::Isometry3d cam = cameraOnRobot();
  std::vector<int> ended;
  std::vector<math::SE2> at_start;
  for (int k = 1; k <= 14; ++k) {
    const std::vector<math::SE2> particles(5, math::SE2(0.1 * k, -0.5, 0.3));
    if (k == 4 || k == 10) at_start = particles;
    const auto contest =
        monitor.observe(&search, math::SE2(), 0.25, yuv, lighting, cam, 99 + k, 3, particles);
    if (!contest) continue;
    ended.push_back(k);
    EXPECT_EQ(contest->candidates, 50u);
    ASSERT_EQ(contest->poses.size(), 55u);
    for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(contest->poses[50 + i].x_m, at_start[i].x_m);
  }
  EXPECT_EQ(ended, (std::vector<int>{6, 12}));

  // A proposal source is asked once per check, on its first image; its poses (whole pairs: 6 of
  // 7) come first in the pool, the rest uniform; a source that proposes nothing leaves it uniform.
  RelocalizationMonitor proposing(config);
  int asked = 0;
  bool propose_none = false;
  const auto propose = [&] {
    ++asked;
    return propose_none ? std::vector<math::SE2>()
                        : std::vector<math::SE2>(7, math::SE2(-2.0, 1.0, 0.5));
  };
  std::vector<std::size_t> proposed;
  for (int k = 1; k <= 12; ++k) {
    propose_none = k > 6;
    const std::vector<math::SE2> particles(5, math::SE2(0.5, -0.5, 0.3));
    const auto contest = proposing.observe(&search, math::SE2(), 0.25, yuv, lighting, cam, k, 3,
                                           particles, propose);
    if (!contest) continue;
    proposed.push_back(proposing.proposed());
    EXPECT_EQ(contest->candidates, 50u);
    ASSERT_EQ(contest->poses.size(), 55u);
    for (std::size_t i = 0; i < proposing.proposed(); ++i) EXPECT_EQ(contest->poses[i].x_m, -2.0);
    for (std::size_t i = proposing.proposed(); i < 50; ++i) EXPECT_NE(contest->poses[i].x_m, -2.0);
  }
  EXPECT_EQ(asked, 2);  // the checks began on images 4 and 10
  EXPECT_EQ(proposed, (std::vector<std::size_t>{6, 0}));

  config.interval_s = 0.0;  // off
  RelocalizationMonitor off(config);
  for (int k = 1; k <= 20; ++k)
    EXPECT_FALSE(off.observe(&search, math::SE2(), 0.25, yuv, lighting, cam, k, 3, {}).has_value());
  config.fraction = 0.0;
  EXPECT_THROW(RelocalizationMonitor{config}, std::invalid_argument);
}
