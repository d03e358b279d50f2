// Goal sightings and the landmarks' hues, on images rendered from the map at known poses (the
// renderer's geometry, independent of the detector's inversion of it).
#include "adaptive_perception/localization/goal_detection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "adaptive_perception/color/color_space.h"
#include "adaptive_perception/color/field_segmentation.h"
#include "adaptive_perception/localization/landmark_colours.h"
#include "adaptive_perception/localization/rbpf_localizer.h"
#include "adaptive_perception/world/label_renderer.h"
#include "adaptive_perception/world/robot_camera.h"

namespace adaptive_perception::localization {
namespace {

const std::string kConfig = std::string(AP_SOURCE_DIR) + "/config/";

struct Scene {
  world::FieldMap map = world::FieldMap::loadYaml(kConfig + "field_spl_landmarks.yaml");
  world::RobotCamera nao = world::RobotCamera::loadYaml(kConfig + "cameras/nao_v6_top.yaml");
  world::LabelRenderer renderer{map, nao.camera};
  // punt1 of the development set: 6 m from the goal at -x, looking at it.
  math::SE2 pose{1.64, 1.02, -153.6 * M_PI / 180.0};
  // The landmarks' paints in the rendered image (sRGB), by class; the hues landmark_colours.h
  // assumes unless a test says otherwise.
  std::map<int, Eigen::Vector3d> paints = {{world::kPink, {255, 105, 180}},
                                           {world::kYellow, {255, 255, 0}},
                                           {world::kCyan, {80, 160, 230}}};
  Eigen::Isometry3d head = nao.baseToOptical(0.0138, 0.0782);

  /// The image the map shows from `pose` with the camera at `base_to_optical`, each class
  /// painted in its paint's colour; the room a dark grey.
  cv::Mat render(const math::SE2& at, const Eigen::Isometry3d& base_to_optical) const {
    cv::Mat labels(nao.camera.height_px, nao.camera.width_px, CV_8UC1);
    renderer.renderImage(world::planarToIsometry(at) * base_to_optical, labels.data);
    cv::Mat yuv(labels.size(), CV_8UC3);
    for (int v = 0; v < labels.rows; ++v) {
      for (int u = 0; u < labels.cols; ++u) {
        Eigen::Vector3d rgb(90, 80, 70);
        const std::uint8_t label = labels.at<std::uint8_t>(v, u);
        if (label == world::kGreen) rgb = {40, 140, 40};
        if (label == world::kWhite) rgb = {235, 235, 235};
        if (paints.count(label)) rgb = paints.at(label);
        const Eigen::Vector3d p = color::rgbToYuv(rgb);
        yuv.at<cv::Vec3b>(v, u) =
            cv::Vec3b(cv::saturate_cast<std::uint8_t>(p[0]), cv::saturate_cast<std::uint8_t>(p[1]),
                      cv::saturate_cast<std::uint8_t>(p[2]));
      }
    }
    return yuv;
  }
  std::vector<GoalSighting> detect(const cv::Mat& yuv, const Eigen::Isometry3d& b2o) const {
    return detectGoals(yuv, color::segmentFieldYuv(yuv, {}), nao.camera, b2o, map, {});
  }
};

/// The pose nearest `truth` among `poses`, and its distance.
double nearest(const std::vector<math::SE2>& poses, const math::SE2& truth, math::SE2* best) {
  double d = 1e9;
  for (const math::SE2& p : poses) {
    const double e = std::hypot(p.x_m - truth.x_m, p.y_m - truth.y_m);
    if (e < d) d = e, *best = p;
  }
  return d;
}

TEST(GoalDetection, FindsTheGoalAndTheRobotsPoseOnARenderedImage) {
  const Scene s;
  const auto goals = s.detect(s.render(s.pose, s.head), s.head);
  ASSERT_EQ(goals.size(), 1u);
  // The feet where the posts of the goal at -x stand, seen from the pose (left in the image: the
  // post at -y, facing -x).
  const math::SE2 inv = s.pose.inverse();
  const auto seen = [&](double x, double y) {
    const math::SE2 p = inv * math::SE2(x, y, 0.0);
    return Eigen::Vector2d(p.x_m, p.y_m);
  };
  // The posts' axes (field_map.cpp): their fronts on the goal line's front edge, x = -4.45,
  // so the axes at -4.5; 0.8 m either side.
  EXPECT_LT((goals[0].left.foot_m - seen(-4.5, -0.8)).norm(), 0.15);
  EXPECT_LT((goals[0].right.foot_m - seen(-4.5, 0.8)).norm(), 0.15);
  EXPECT_NEAR(goals[0].pitch_offset_rad, 0.0, 0.01);
  const auto poses = goalPoses(goals[0], s.map);
  ASSERT_EQ(poses.size(), 2u);
  math::SE2 best;
  // Where on the circle through the posts the robot stands rests on the ratio of the posts'
  // ranges, from their feet's rows: at 6 m, head-on, one row (2% of the range) moves the pose
  // 0.47 m along that circle.
  EXPECT_LT(nearest(poses, s.pose, &best), 0.47);
  // The heading rests on the ratio of the posts' ranges, from their feet's rows: at 6 m one row
  // is 2% of the range, and 2% of 6 m across the goal's 1.6 m turns the heading by 0.075 rad.
  EXPECT_NEAR(math::wrapAngle(best.yaw_rad - s.pose.yaw_rad), 0.0, 0.075);
  // The other is its point mirror (the other goal).
  const math::SE2 m = math::pointMirror(best);
  EXPECT_LT(nearest(poses, m, &best), 1e-9);
}

TEST(GoalDetection, MeasuresTheBodysLeanTheHeadChainDoesNotKnow) {
  const Scene s;
  for (const double head_yaw : {0.0138, 0.5}) {
    // The body leans forward by 0.04 rad; with the head turned by 0.5 rad the lean tilts the
    // camera about an axis that is not the camera's own (the robot turned so that the goal stays
    // in view).
    const double lean = 0.04;
    const Eigen::Isometry3d head = s.nao.baseToOptical(head_yaw, 0.0782);
    const math::SE2 pose(s.pose.x_m, s.pose.y_m, s.pose.yaw_rad - head_yaw + 0.0138);
    const auto goals = s.detect(s.render(pose, leanCamera(head, lean)), head);
    ASSERT_EQ(goals.size(), 1u) << "head yaw " << head_yaw;
    EXPECT_NEAR(goals[0].pitch_offset_rad, lean, 0.004) << "head yaw " << head_yaw;
    math::SE2 best;
    EXPECT_LT(nearest(goalPoses(goals[0], s.map), pose, &best), 0.47) << "head yaw " << head_yaw;
  }
}

// Two window mullions against a bright sky look like posts with a white crossbar anywhere
// between them (the NAO development point punt3): what a goal's mouth shows must not be white.
TEST(GoalDetection, AWhiteFrameAroundAWhiteMouthIsNotAGoal) {
  const Scene s;
  cv::Mat yuv = s.render(s.pose, s.head);
  ASSERT_EQ(s.detect(yuv, s.head).size(), 1u);  // the control: the goal before a dark room
  // The room seen through the goal's mouth, from 0.3 m up to the crossbar, turned white (sky);
  // below that it stays dark, so the mouth's white does not reach the posts' feet.
  cv::Mat labels(s.nao.camera.height_px, s.nao.camera.width_px, CV_8UC1);
  s.renderer.renderImage(world::planarToIsometry(s.pose) * s.head, labels.data);
  const Eigen::Isometry3d optical_from_map = (world::planarToIsometry(s.pose) * s.head).inverse();
  const Eigen::Vector3d sky = color::rgbToYuv(Eigen::Vector3d(235, 238, 240));
  int painted = 0;
  for (double y = -0.75; y <= 0.75; y += 0.005) {
    for (double z = 0.3; z <= 0.8; z += 0.005) {
      Eigen::Vector2d uv;
      if (!s.nao.camera.project(optical_from_map * Eigen::Vector3d(-4.52, y, z), &uv)) continue;
      const int u = static_cast<int>(std::lround(uv.x())),
                v = static_cast<int>(std::lround(uv.y()));
      if (u < 0 || v < 0 || u >= yuv.cols || v >= yuv.rows) continue;
      if (labels.at<std::uint8_t>(v, u) != world::kBackground) continue;
      yuv.at<cv::Vec3b>(v, u) =
          cv::Vec3b(static_cast<std::uint8_t>(sky[0]), static_cast<std::uint8_t>(sky[1]),
                    static_cast<std::uint8_t>(sky[2]));
      ++painted;
    }
  }
  ASSERT_GT(painted, 100);
  EXPECT_TRUE(s.detect(yuv, s.head).empty());
  // Without the mouth check the frame passes for a goal: the check is what refuses it.
  GoalDetectionConfig lax;
  lax.mouth_max_white_share = 1.0;
  EXPECT_EQ(
      detectGoals(yuv, color::segmentFieldYuv(yuv, {}), s.nao.camera, s.head, s.map, lax).size(),
      1u);
}

TEST(GoalDetection, NothingWithoutPostsOrWithoutAGoalInView) {
  const Scene s;
  // Facing the side line: no goal in view.
  const math::SE2 side(0.5, -1.0, M_PI / 2);
  EXPECT_TRUE(s.detect(s.render(side, s.head), s.head).empty());
  // The four-legged field's goals are panels, not posts.
  const world::FieldMap four(world::FieldDimensions{});
  const cv::Mat yuv = s.render(s.pose, s.head);
  EXPECT_TRUE(
      detectGoals(yuv, color::segmentFieldYuv(yuv, {}), s.nao.camera, s.head, four, {}).empty());
}

TEST(GoalDetection, RefusesAnImageOfAnotherKindOrLabelsOfAnotherSize) {
  const Scene s;
  const cv::Mat yuv = s.render(s.pose, s.head);
  const color::FieldSegmentation seg = color::segmentFieldYuv(yuv, {});
  const cv::Mat grey(yuv.size(), CV_8UC1, cv::Scalar(128));
  EXPECT_THROW(detectGoals(grey, seg, s.nao.camera, s.head, s.map, {}), std::invalid_argument);
  color::FieldSegmentation half = seg;
  cv::resize(seg.labels, half.labels, cv::Size(), 0.5, 0.5, cv::INTER_NEAREST);
  EXPECT_THROW(detectGoals(yuv, half, s.nao.camera, s.head, s.map, {}), std::invalid_argument);
}

TEST(GoalDetection, SamplesArePointMirroredPairsOnTheCarpetAroundTheTruth) {
  const Scene s;
  const auto goals = s.detect(s.render(s.pose, s.head), s.head);
  ASSERT_EQ(goals.size(), 1u);
  math::Rng rng(3);
  const auto samples = sampleGoalPoses(goals[0], s.map, GoalDetectionConfig{}, 2000, rng);
  ASSERT_GE(samples.size(), 1900u);
  ASSERT_EQ(samples.size() % 2, 0u);
  int near = 0;
  for (std::size_t k = 0; k < samples.size(); k += 2) {
    const math::SE2 m = math::pointMirror(samples[k]);
    EXPECT_NEAR(samples[k + 1].x_m, m.x_m, 1e-9);
    EXPECT_NEAR(samples[k + 1].y_m, m.y_m, 1e-9);
    EXPECT_NEAR(math::wrapAngle(samples[k + 1].yaw_rad - m.yaw_rad), 0.0, 1e-9);
    for (const math::SE2& p : {samples[k], samples[k + 1]}) {
      EXPECT_TRUE(s.map.isFree(p.x_m, p.y_m, 0.0));
      near += std::hypot(p.x_m - s.pose.x_m, p.y_m - s.pose.y_m) < 0.2 &&
              std::abs(math::wrapAngle(p.yaw_rad - s.pose.yaw_rad)) < 0.05;
    }
  }
  EXPECT_GT(near, 10);
  // With no uncertainty every draw is goalPoses() (up to the pitch bisection's precision).
  GoalDetectionConfig exact;
  exact.goal_range_ratio_sd = 0.0;
  exact.goal_bearing_sd_rad = 0.0;
  const auto same = sampleGoalPoses(goals[0], s.map, exact, 4, rng);
  const auto poses = goalPoses(goals[0], s.map);
  ASSERT_EQ(same.size(), 4u);
  EXPECT_NEAR(same[2].x_m, poses[0].x_m, 1e-6);
  EXPECT_NEAR(same[3].y_m, poses[1].y_m, 1e-6);
}

// The localizer's use of a sighting: a global start's first image fills the pool from the goal
// (the particles drawn from it lie on the goal's two arcs) and measures the lean, which the
// filter then adds to the camera; a pose given by hand drops it.
TEST(GoalDetection, AGlobalStartTakesItsPoolAndTheLeanFromTheGoal) {
  const Scene s;
  const std::vector<color::LightingPrior> priors = {
      color::LightingPrior::loadYaml(kConfig + "color_priors/dark.yaml"),
      color::LightingPrior::loadYaml(kConfig + "color_priors/bright.yaml")};
  RbpfConfig cfg;
  cfg.particles = 200;
  cfg.threads = 2;
  cfg.global.goal_pool_size = 4000;
  cfg.relocalization.interval_s = 0.0;
  const double lean = 0.03;
  const cv::Mat yuv = s.render(s.pose, leanCamera(s.head, lean));
  RbpfLocalizer rbpf(s.map, s.nao.camera, priors, cfg);
  rbpf.initUniform();
  const RbpfLocalizer::StepResult first = rbpf.step(math::SE2(), 0.0, yuv, s.head);
  EXPECT_EQ(first.goal_sightings, 1);
  EXPECT_NEAR(first.camera_pitch_offset_rad, lean, 0.004);
  // Every particle sees one of the goals' posts as far apart as the truth sees them (the arc the
  // sighting leaves open), up to the sampled bearings' spread (0.01 rad each, so 4 sigma).
  const auto subtended = [](const math::SE2& p, double goal_x) {
    return std::abs(math::wrapAngle(std::atan2(0.8 - p.y_m, goal_x - p.x_m) -
                                    std::atan2(-0.8 - p.y_m, goal_x - p.x_m)));
  };
  const double truth = subtended(s.pose, -4.5);
  for (const Particle& p : rbpf.particles()) {
    EXPECT_LT(std::min(std::abs(subtended(p.pose, -4.5) - truth),
                       std::abs(subtended(p.pose, 4.5) - truth)),
              4 * std::sqrt(2.0) * 0.01);
  }
  const RbpfLocalizer::StepResult second = rbpf.step(math::SE2(), 1.0 / 30, yuv, s.head);
  EXPECT_EQ(second.goal_sightings, -1);  // looked for at a search's first image only
  EXPECT_NEAR(second.camera_pitch_offset_rad, lean, 0.004);
  rbpf.initGaussian(s.pose, Eigen::Matrix3d::Identity() * 1e-4);
  EXPECT_EQ(rbpf.step(math::SE2(), 1.0 / 30, yuv, s.head).camera_pitch_offset_rad, 0.0);
}

// The room's colours from the image (background_from_image), its boundary found on the image
// shrunk to background_width_px (320 of 640 here) or at full size: either way the filter given
// the true pose keeps it (the rendered room is one colour, which the density learns).
TEST(GoalDetection, AKnownStartHoldsWithTheRoomsColoursFromTheImage) {
  const Scene s;
  const std::vector<color::LightingPrior> priors = {
      color::LightingPrior::loadYaml(kConfig + "color_priors/dark.yaml"),
      color::LightingPrior::loadYaml(kConfig + "color_priors/bright.yaml")};
  const cv::Mat yuv = s.render(s.pose, s.head);
  // What the shrinking rests on: the background found at 320 px, scaled back, is the one found at
  // 640 px but for a few pixels along the boundary.
  cv::Mat small, above_small;
  cv::resize(yuv, small, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
  cv::resize(color::segmentFieldYuv(small, {}).labels == world::kBackground, above_small,
             yuv.size(), 0, 0, cv::INTER_NEAREST);
  const cv::Mat above = color::segmentFieldYuv(yuv, {}).labels == world::kBackground;
  EXPECT_LT(cv::countNonZero(above != above_small), 0.01 * yuv.total());
  EXPECT_GT(cv::countNonZero(above), 0.1 * yuv.total());
  for (const int width : {320, 640}) {
    RbpfConfig cfg;
    cfg.particles = 200;
    cfg.threads = 2;
    cfg.relocalization.interval_s = 0.0;
    cfg.likelihood.background_from_image = true;
    cfg.likelihood.background_width_px = width;
    RbpfLocalizer rbpf(s.map, s.nao.camera, priors, cfg);
    rbpf.initGaussian(s.pose, Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 0.03 * 0.03).asDiagonal());
    for (int k = 0; k < 5; ++k) rbpf.step(math::SE2(), k == 0 ? 0.0 : 1.0 / 30, yuv, s.head);
    const PoseEstimate e = rbpf.estimate();
    EXPECT_LT(std::hypot(e.pose.x_m - s.pose.x_m, e.pose.y_m - s.pose.y_m), 0.1) << width;
    EXPECT_LT(std::abs(math::wrapAngle(e.pose.yaw_rad - s.pose.yaw_rad)), 0.03) << width;
  }
}

TEST(LandmarkColours, TheHuesTellAPoseFromItsMirror) {
  const Scene s;
  // punt5 of the development set: the landmark yellow over pink in view.
  const math::SE2 pose(-1.03, 0.51, -23.4 * M_PI / 180.0);
  const Eigen::Isometry3d head = s.nao.baseToOptical(0.0138, -0.1304);
  const cv::Mat yuv = s.render(pose, head);
  const LandmarkColourConfig config;
  const LandmarkColourEvidence at_truth =
      landmarkMirrorEvidence(yuv, s.renderer, pose, head, config);
  ASSERT_EQ(at_truth.landmarks, 1);  // yellow over pink, against pink over cyan
  // Both templates are scored where the landmark is: the pose's bands fit exactly (score 2: two
  // hued bands, cosine 1); the mirror's (cyan below pink) lie cyan on pink and pink on yellow. By
  // hand from the paints' (U, V): cos(cyan, pink) = -0.55, cos(pink, yellow) = -0.01. The bands'
  // edges, rounded to rows of a band some 9 pixels tall, put a row of neutral pixels (similarity 0)
  // into a band here and there: they only shrink both scores towards 0, so the evidence lies
  // between the exact value and some 80% of it.
  const auto hue = [](double r, double g, double b) {
    const Eigen::Vector3d y = color::rgbToYuv({r, g, b});
    return Eigen::Vector2d(y[1] - 128, y[2] - 128).normalized();
  };
  const Eigen::Vector2d pink = hue(255, 105, 180), yellow = hue(255, 255, 0),
                        cyan = hue(80, 160, 230);
  EXPECT_NEAR(cyan.dot(pink), -0.55, 0.01);
  const double expected = config.concentration * (cyan.dot(pink) + pink.dot(yellow) - 2.0);
  EXPECT_GT(at_truth.mirror_minus_pose_nats, expected - 0.01);
  EXPECT_LT(at_truth.mirror_minus_pose_nats, 0.8 * expected);
  // From the mirror, the same evidence the other way.
  const LandmarkColourEvidence at_mirror =
      landmarkMirrorEvidence(yuv, s.renderer, math::pointMirror(pose), head, config);
  EXPECT_NEAR(at_mirror.mirror_minus_pose_nats, -at_truth.mirror_minus_pose_nats, 0.05);
  // Painted otherwise than the hues the test assumes (a paler pink, an orange-yellow, a darker
  // sky-blue, as a real camera shows them), the truth still wins by more than a nat per band.
  Scene other = s;
  other.paints = {{world::kPink, {230, 120, 160}},
                  {world::kYellow, {230, 200, 60}},
                  {world::kCyan, {60, 130, 190}}};
  const LandmarkColourEvidence repainted =
      landmarkMirrorEvidence(other.render(pose, head), s.renderer, pose, head, config);
  EXPECT_LT(repainted.mirror_minus_pose_nats, -2.0);
  // A grey image has no hues: no landmark is seen, nothing is said.
  const cv::Mat grey(yuv.size(), CV_8UC3, cv::Scalar(128, 128, 128));
  const LandmarkColourEvidence none = landmarkMirrorEvidence(grey, s.renderer, pose, head, config);
  EXPECT_EQ(none.landmarks, 0);
  EXPECT_EQ(none.mirror_minus_pose_nats, 0.0);
}

TEST(LandmarkColours, ABacklitLandmarkDoesNotSendThePoseToItsMirror) {
  // punt3 of the development set, against the hall's windows: its two landmarks (pink over cyan at
  // the left, pink over green at the right edge, cut by it) are backlit. Their paints as the
  // camera shows them there: the pink band dark red, the cyan and green bands dark and all but
  // neutral, the white base yellow-brown (chroma 26 levels, more than the hued bands have).
  Scene s;
  s.paints = {{world::kPink, {48, 20, 15}},
              {world::kCyan, {15, 25, 20}},
              {world::kGreen, {22, 16, 5}},
              {world::kWhite, {81, 65, 22}}};
  const math::SE2 pose(0.568, -1.091, 124.0 * M_PI / 180.0);
  const Eigen::Isometry3d head = s.nao.baseToOptical(-0.0031, -0.0031);
  const cv::Mat yuv = s.render(pose, head);
  const LandmarkColourConfig config;
  // The mirror's yellow-over-pink would fit if its bands could slide a whole band down onto the
  // yellowish base (a window of one and a half bases), or if the landmark at the image's edge
  // were scored on the column left in view; neither may give the mirror evidence.
  const LandmarkColourEvidence e = landmarkMirrorEvidence(yuv, s.renderer, pose, head, config);
  EXPECT_LE(e.mirror_minus_pose_nats, 0.0);
  // Seen from the mirror the same pixels must not favour staying there either.
  const LandmarkColourEvidence m =
      landmarkMirrorEvidence(yuv, s.renderer, math::pointMirror(pose), head, config);
  EXPECT_GE(m.mirror_minus_pose_nats, 0.0);
  // The same view with the paints' own hues: the landmarks are scored (the one at the right edge
  // where a shift within its window brings its hued bands wholly into the image) and tell the
  // pose from its mirror.
  const Scene lit;
  const LandmarkColourEvidence seen =
      landmarkMirrorEvidence(lit.render(pose, head), lit.renderer, pose, head, config);
  EXPECT_GE(seen.landmarks, 1);
  EXPECT_LT(seen.mirror_minus_pose_nats, -2.0);
}

// The image `yuv` as under a light that scales R, G and B by `light` (rounded, clipped).
cv::Mat underLight(const cv::Mat& yuv, const Eigen::Vector3d& light) {
  cv::Mat out(yuv.size(), CV_8UC3);
  for (int v = 0; v < yuv.rows; ++v)
    for (int u = 0; u < yuv.cols; ++u) {
      const cv::Vec3b& p = yuv.at<cv::Vec3b>(v, u);
      const Eigen::Vector3d rgb =
          color::yuvToRgb(Eigen::Vector3d(p[0], p[1], p[2])).cwiseProduct(light);
      const Eigen::Vector3d q = color::rgbToYuv(rgb);
      out.at<cv::Vec3b>(v, u) =
          cv::Vec3b(cv::saturate_cast<std::uint8_t>(q[0]), cv::saturate_cast<std::uint8_t>(q[1]),
                    cv::saturate_cast<std::uint8_t>(q[2]));
    }
  return out;
}

TEST(LandmarkColours, ADimCoolLightIsBalancedAwayBeforeTheHuesAreRead) {
  // punt4's view of the development set, its landmarks' pink faded as it is there (chroma 19,
  // luma 214): under a light 0.55 times as bright and cool (R, G, B by 0.47, 0.52, 0.55), where
  // the pink's chroma falls to 6 levels, below LandmarkColourConfig::min_chroma.
  Scene s;
  s.paints[world::kPink] = {240, 200, 215};
  const math::SE2 pose(-2.12, 0.03, 0.02);
  const Eigen::Isometry3d head = s.nao.baseToOptical(0.006, 0.061);
  const cv::Mat seen = s.render(pose, head);
  const Eigen::Vector3d light(0.55 * 0.85, 0.55 * 0.95, 0.55);
  const cv::Mat tinted = underLight(seen, light);
  const LandmarkColourConfig config;
  const LandmarkColourEvidence truth = landmarkMirrorEvidence(seen, s.renderer, pose, head, config);
  ASSERT_GE(truth.landmarks, 1);
  ASSERT_LT(truth.mirror_minus_pose_nats, -1.0);
  // The localizer takes the balance from the paint of its first image.
  RbpfConfig cfg;
  cfg.particles = 50;
  cfg.adapt_priors_to_image = true;
  const std::vector<color::LightingPrior> priors = {
      color::LightingPrior::loadYaml(kConfig + "color_priors/dark.yaml"),
      color::LightingPrior::loadYaml(kConfig + "color_priors/bright.yaml")};
  RbpfLocalizer rbpf(s.map, s.nao.camera, priors, cfg);
  rbpf.initGaussian(pose, Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 0.03 * 0.03).asDiagonal());
  rbpf.step(math::SE2(), 0.0, tinted, head);
  const color::WhiteBalance& wb = rbpf.whiteBalance();
  ASSERT_FALSE(wb.identity);
  // Its gains undo the light (the rendered paint is grey, 235) up to the exposure, which brings
  // the paint to paint_luma: gain * light = paint_luma / 235 in each channel.
  const Eigen::Vector3d undone = wb.gains_rgb.cwiseProduct(light);
  const double exposure = cfg.white_balance.paint_luma / 235.0;
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(undone[ch], exposure, 0.02) << "channel " << ch;
  // Read after the balance, the landmark gives the evidence it gives under the light it was seen
  // in; read as it comes, it does not.
  const LandmarkColourEvidence balanced =
      landmarkMirrorEvidence(wb.apply(tinted), s.renderer, pose, head, config);
  EXPECT_EQ(balanced.landmarks, truth.landmarks);
  // (Within 5%: the dim image's levels come out 1.8 times coarser after the balance.)
  EXPECT_NEAR(balanced.mirror_minus_pose_nats, truth.mirror_minus_pose_nats,
              0.05 * std::abs(truth.mirror_minus_pose_nats));
  const LandmarkColourEvidence raw = landmarkMirrorEvidence(tinted, s.renderer, pose, head, config);
  EXPECT_EQ(raw.landmarks, 0);  // every band below min_chroma
  EXPECT_GT(std::abs(raw.mirror_minus_pose_nats - truth.mirror_minus_pose_nats),
            0.5 * std::abs(truth.mirror_minus_pose_nats))
      << raw.mirror_minus_pose_nats << " against " << truth.mirror_minus_pose_nats;
  // Without balance_to_paint the images are read as they come; a new start forgets the balance.
  RbpfConfig off = cfg;
  off.balance_to_paint = false;
  RbpfLocalizer plain(s.map, s.nao.camera, priors, off);
  plain.initGaussian(pose, Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 0.03 * 0.03).asDiagonal());
  plain.step(math::SE2(), 0.0, tinted, head);
  EXPECT_TRUE(plain.whiteBalance().identity);
  rbpf.initUniform();
  EXPECT_TRUE(rbpf.whiteBalance().identity);
}

TEST(LandmarkColours, ABalanceIsTakenLaterWhenTheFirstImageShowsNoPaint) {
  // The first image after a start shows carpet only (the head down at a bare patch): the priors
  // are adapted to it, without a balance; the balance comes from the first retried image that
  // shows paint, balance_retry_images later.
  Scene s;
  const math::SE2 pose(-2.12, 0.03, 0.02);
  const Eigen::Isometry3d head = s.nao.baseToOptical(0.006, 0.061);
  const Eigen::Vector3d light(0.9, 0.8, 0.6);
  const cv::Mat view = underLight(s.render(pose, head), light);
  cv::Mat carpet = view.clone();
  carpet.setTo(view.at<cv::Vec3b>(view.rows - 1, view.cols / 2));  // the carpet's colour
  RbpfConfig cfg;
  cfg.particles = 50;
  cfg.adapt_priors_to_image = true;
  cfg.balance_retry_images = 3;
  const std::vector<color::LightingPrior> priors = {
      color::LightingPrior::loadYaml(kConfig + "color_priors/dark.yaml"),
      color::LightingPrior::loadYaml(kConfig + "color_priors/bright.yaml")};
  RbpfLocalizer rbpf(s.map, s.nao.camera, priors, cfg);
  rbpf.initGaussian(pose, Eigen::Vector3d(0.05 * 0.05, 0.05 * 0.05, 0.03 * 0.03).asDiagonal());
  rbpf.step(math::SE2(), 0.0, carpet, head);
  EXPECT_TRUE(rbpf.whiteBalance().identity);
  rbpf.step(math::SE2(), 1.0 / 30, view, head);
  rbpf.step(math::SE2(), 1.0 / 30, view, head);
  EXPECT_TRUE(rbpf.whiteBalance().identity);  // not yet the third image
  rbpf.step(math::SE2(), 1.0 / 30, view, head);
  ASSERT_FALSE(rbpf.whiteBalance().identity);
  const Eigen::Vector3d undone = rbpf.whiteBalance().gains_rgb.cwiseProduct(light);
  EXPECT_NEAR(undone[1] / undone[0], 1.0, 0.02);
  EXPECT_NEAR(undone[2] / undone[0], 1.0, 0.02);
}

}  // namespace
}  // namespace adaptive_perception::localization
