// tracking::BoxCondensationTracker: configuration checks, bad input, and tracking the project's
// simulated sequences (a moving target among clutter; a distractor of the target's colour
// crossing it) against their ground truth, with the default configuration.
#include "adaptive_perception/tracking/box_condensation_tracker.h"
#include "adaptive_perception/tracking/redetection.h"

#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "../refusal.h"
#include "adaptive_perception/sim/tracking_scene.h"
#include "adaptive_perception/tracking/benchmark_metrics.h"

namespace tr = adaptive_perception::tracking;
namespace sim = adaptive_perception::sim;
using adaptive_perception::test_support::refusedNaming;

namespace {

/// Success rate (IoU >= 0.5, every frame after the first) on a simulated sequence.
double successOn(sim::TrackingScenario scenario, std::uint64_t seed, bool grey = false) {
  sim::TrackingSceneConfig sc;
  sc.scenario = scenario;
  sc.frames = 150;
  sim::TrackingScene scene(sc, seed);
  tr::BoxCondensationTracker tracker(tr::BoxTrackerConfig{}, seed);
  int frames = 0, success = 0;
  while (!scene.done()) {
    const sim::SceneFrame f = scene.next();
    cv::Mat image = f.bgr;
    if (grey) cv::cvtColor(f.bgr, image, cv::COLOR_BGR2GRAY);
    if (!tracker.initialized()) {
      tracker.init(image, f.truth);
      continue;
    }
    const tr::BoxTrackResult r = tracker.track(image);
    ++frames;
    success += tr::boxIou(r.box, f.truth) >= 0.5;
  }
  return static_cast<double>(success) / frames;
}

// A red and blue checked target over a fixed textured background, and a grey textured board that
// can stand in front of it (ReportsAHiddenTargetLost, ReDetectsATargetThatComesBackElsewhere).
struct HiddenTargetScene {
  cv::Mat background, board;
  HiddenTargetScene() : background(240, 320, CV_8UC3), board(90, 80, CV_8UC3) {
    cv::theRNG().state = 12345;
    cv::randu(background, cv::Scalar::all(60), cv::Scalar::all(200));
    cv::GaussianBlur(background, background, cv::Size(0, 0), 2.0);
    cv::randu(board, cv::Scalar::all(100), cv::Scalar::all(140));
  }
  /// The target at `target`, the board's top-left at `board_at` (none when negative).
  cv::Mat frame(const cv::Rect& target, cv::Point board_at) const {
    cv::Mat img = background.clone();
    for (int y = 0; y < target.height; ++y)
      for (int x = 0; x < target.width; ++x)
        img.at<cv::Vec3b>(target.y + y, target.x + x) =
            ((x / 6 + y / 6) % 2) ? cv::Vec3b(200, 40, 30) : cv::Vec3b(30, 40, 210);
    if (board_at.x >= 0) board.copyTo(img(cv::Rect(board_at, board.size())));
    return img;
  }
};

}  // namespace

TEST(BoxTrackerConfig, RejectsBadFieldsByName) {
  tr::BoxTrackerConfig c;
  EXPECT_NO_THROW(c.validate());
  c.bins_per_channel = 12;  // not a power of two
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "bins_per_channel"));
  c = {};
  c.ring_scale = 1.0;
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "ring_scale"));
  c = {};
  c.position_noise = std::nan("");
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "position_noise"));
  c = {};
  c.template_cells = 2;
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "template_cells"));
  c = {};
  c.scale_filter_share = 1.5;
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "scale_filter_share"));
  c = {};
  c.scale.scales = 4;
  EXPECT_TRUE(refusedNaming([&] { c.validate(); }, "scale.scales"));
}

TEST(BoxCondensationTracker, RefusesBadImagesAndBoxes) {
  tr::BoxCondensationTracker t;
  const cv::Mat image(120, 160, CV_8UC3, cv::Scalar(40, 80, 120));
  EXPECT_THROW(t.track(image), std::logic_error);
  EXPECT_THROW(t.init(image, {10, 10, 2, 20}), std::invalid_argument);     // too small
  EXPECT_THROW(t.init(image, {500, 500, 20, 20}), std::invalid_argument);  // outside
  EXPECT_THROW(t.init(cv::Mat(120, 160, CV_32FC1), {10, 10, 20, 20}), std::invalid_argument);
  t.init(image, {10, 10, 20, 20});
  EXPECT_THROW(t.track(cv::Mat(120, 160, CV_16UC3)), std::invalid_argument);
  const tr::BoxTrackResult r = t.track(image);  // a flat image: no crash, a box of the right size
  EXPECT_GT(r.box.width, 0.0);
}

// (The Lambertian rectangle, which turns and changes its shading as it revolves around the light,
// is not here: this tracker loses it; see the tracking issue's note.)
TEST(BoxCondensationTracker, FollowsSimulatedTargetsInColourAndInGrey) {
  EXPECT_GE(successOn(sim::TrackingScenario::kCircles, 1), 0.9);
  EXPECT_GE(successOn(sim::TrackingScenario::kCircles, 2, true), 0.8);
}

TEST(BoxCondensationTracker, IsNotTakenAwayByADistractorOfTheSameColour) {
  EXPECT_GE(successOn(sim::TrackingScenario::kDistractor, 1), 0.8);
}

TEST(BoxCondensationTracker, TheSameSeedGivesTheSameTrack) {
  sim::TrackingSceneConfig sc;
  sc.frames = 20;
  std::vector<cv::Rect2d> runs[2];
  for (auto& run : runs) {
    sim::TrackingScene scene(sc, 3);
    tr::BoxCondensationTracker t(tr::BoxTrackerConfig{}, 7);
    const sim::SceneFrame first = scene.next();
    t.init(first.bgr, first.truth);
    while (!scene.done()) run.push_back(t.track(scene.next().bgr).box);
  }
  EXPECT_EQ(runs[0], runs[1]);
}

TEST(BoxCondensationTracker, FollowsACameraComingCloserAndTheHandheldScene) {
  // A textured scene zoomed about its centre by 1% a frame for 60 frames (the camera comes
  // closer): the box must grow with it, 1.01^60 = 1.82 times, and stay on the same texture.
  cv::Mat noise(240, 320, CV_8UC3);
  cv::RNG rng(3);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 255);
  cv::Mat scene;
  cv::GaussianBlur(noise, scene, cv::Size(), 2.0);
  const cv::Rect2d first(140, 100, 40, 40);
  const double zoom = std::pow(1.01, 60);
  const cv::Rect2d truth(160 - 20 * zoom, 120 - 20 * zoom, 40 * zoom, 40 * zoom);
  // With the scale from the correlation filter (the default) and from the scale filter alone.
  tr::BoxTrackerConfig with_scale_filter;
  with_scale_filter.scale_filter_share = 1.0;
  for (const tr::BoxTrackerConfig& config : {tr::BoxTrackerConfig{}, with_scale_filter}) {
    tr::BoxCondensationTracker tracker(config, 1);
    tracker.init(scene, first);
    tr::BoxTrackResult r;
    for (int k = 1; k <= 60; ++k) {
      const double z = std::pow(1.01, k);
      const cv::Matx23d m(z, 0, 160 * (1 - z), 0, z, 120 * (1 - z));
      cv::Mat frame;
      cv::warpAffine(scene, frame, cv::Mat(m), scene.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
      r = tracker.track(frame);
    }
    EXPECT_GT(tr::boxIou(r.box, truth), 0.8) << r.box << " scale_filter_share "
                                              << config.scale_filter_share;
    EXPECT_NEAR(r.box.width / truth.width, 1.0, 0.1);
  }
  // The real-video-like simulated scene (textured background, shake, blur, light ramp).
  EXPECT_GE(successOn(sim::TrackingScenario::kHandheld, 1), 0.9);
}

// A red and blue checked target drifts right over a fixed textured background; from frame 40 to
// 59 a grey textured board stands in front of it. While it is visible the response and colours
// stay near their means (at most one frame reported lost); hidden, both fall, and most hidden
// frames are reported lost (BoxTrackerConfig::reliable_peak_ratio), although no colour of the
// target is left to score.
TEST(BoxCondensationTracker, ReportsAHiddenTargetLost) {
  const HiddenTargetScene scene;
  auto frame = [&](int t, cv::Rect2d* truth) {
    const cv::Rect target(60 + t, 100, 30, 40);
    *truth = target;
    return scene.frame(target, t >= 40 && t < 60 ? cv::Point(target.x - 25, target.y - 25)
                                                 : cv::Point(-1, -1));
  };
  tr::BoxCondensationTracker tracker(tr::BoxTrackerConfig{}, 3);
  cv::Rect2d truth;
  tracker.init(frame(0, &truth), truth);
  int lost_visible = 0, lost_hidden = 0, hidden = 0;
  for (int t = 1; t < 60; ++t) {
    const tr::BoxTrackResult r = tracker.track(frame(t, &truth));
    if (t < 40) {
      lost_visible += r.lost;
      EXPECT_GT(tr::boxIou(r.box, truth), 0.5) << t;
    } else {
      ++hidden;
      lost_hidden += r.lost;
    }
  }
  std::printf("reported lost: %d of 39 visible frames, %d of %d hidden\n", lost_visible,
              lost_hidden, hidden);
  EXPECT_LE(lost_visible, 1);
  EXPECT_GE(lost_hidden, hidden / 2);
}

// The hidden target of ReportsAHiddenTargetLost comes out from behind the board somewhere else
// (120 px right and 60 px down of where it went in, as if the camera had jumped): the samples,
// spread about where it was lost, do not reach it; the whole-frame search
// (redetect_after_frames) finds it by its colours and its correlation filter together, and the
// box follows it again.
TEST(BoxCondensationTracker, ReDetectsATargetThatComesBackElsewhere) {
  const HiddenTargetScene scene;
  auto frame = [&](int t, cv::Rect2d* truth) {
    const cv::Rect target =
        t < 60 ? cv::Rect(60 + t, 100, 30, 40) : cv::Rect(180 + t - 60, 160, 30, 40);
    *truth = target;
    return scene.frame(target, t >= 40 ? cv::Point(75, 75) : cv::Point(-1, -1));
  };
  const auto run = [&](int redetect_after_frames, int* redetections) {
    tr::BoxTrackerConfig c;
    c.redetect_after_frames = redetect_after_frames;
    tr::BoxCondensationTracker tracker(c, 3);
    cv::Rect2d truth;
    tracker.init(frame(0, &truth), truth);
    int on_target = 0;
    *redetections = 0;
    for (int t = 1; t < 100; ++t) {
      const tr::BoxTrackResult r = tracker.track(frame(t, &truth));
      *redetections += r.redetected;
      if (t >= 80) on_target += tr::boxIou(r.box, truth) > 0.5;
    }
    return on_target;
  };
  int redetections = 0;
  EXPECT_EQ(run(0, &redetections), 0) << "without the search the target must stay lost";
  EXPECT_EQ(redetections, 0);
  EXPECT_EQ(run(tr::BoxTrackerConfig().redetect_after_frames, &redetections), 20)
      << "the last 20 frames, after the search (the default)";
  EXPECT_GE(redetections, 1);
}

// The places of colourPlaces: two blobs of the target's colours on an empty map, the stronger one
// first, each at its centre; a strip too close to a better place is not a place of its own.
TEST(ColourPlaces, FindsTheBlobsBestFirst) {
  cv::Mat p(200, 300, CV_32F, cv::Scalar(0.1f));
  // On the grid of a 30 x 40 box (centres 15 px and 20 px apart).
  p(cv::Rect(45, 40, 30, 40)).setTo(0.9f);    // centre (60, 60)
  p(cv::Rect(195, 120, 30, 40)).setTo(0.7f);  // centre (210, 140)
  p(cv::Rect(227, 120, 6, 40)).setTo(0.6f);   // beside the second: no place of its own
  const auto places = tr::colourPlaces(p, cv::Size2d(30, 40), 1.6, 5);
  ASSERT_GE(places.size(), 2u);
  EXPECT_EQ(places[0].centre, cv::Point2d(60, 60));
  EXPECT_EQ(places[1].centre, cv::Point2d(210, 140));
  EXPECT_NEAR(places[0].score, 0.8, 1e-6);  // 0.9 inside, 0.1 in the ring
  EXPECT_GT(places[0].score, places[1].score);
  for (std::size_t k = 2; k < places.size(); ++k) EXPECT_LT(places[k].score, 0.2) << k;
  EXPECT_THROW(tr::colourPlaces(cv::Mat(), cv::Size2d(30, 40), 1.6, 5), std::invalid_argument);
}

// A target red above and blue below stands still next to an all-red block of its size, a gap of
// a fifth of its width away. The block is found as a distractor, and the red the two share comes
// to count for less than the blue only the target has; without distractors (distractor_ratio 0)
// both colours of the target count alike.
TEST(BoxCondensationTracker, ColoursALookAlikeSharesCountForLess) {
  cv::Mat image(200, 240, CV_8UC3);
  cv::theRNG().state = 777;
  cv::randu(image, cv::Scalar::all(90), cv::Scalar::all(150));
  const cv::Rect target(90, 80, 20, 40), block(114, 80, 20, 40);
  image(cv::Rect(target.x, target.y, 20, 20)).setTo(cv::Scalar(30, 30, 210));
  image(cv::Rect(target.x, target.y + 20, 20, 20)).setTo(cv::Scalar(210, 40, 30));
  image(block).setTo(cv::Scalar(30, 30, 210));
  auto run = [&](double ratio, tr::BoxTrackResult* last) {
    tr::BoxTrackerConfig c;
    c.distractor_ratio = ratio;
    tr::BoxCondensationTracker tracker(c, 5);
    tracker.init(image, target);
    int with_distractor = 0;
    for (int t = 0; t < 30; ++t) {
      *last = tracker.track(image);
      for (const cv::Rect2d& d : last->distractors)
        with_distractor += (d & cv::Rect2d(block)).area() >= 0.5 * d.area();
    }
    // P(O | c) at the centre of the red half and of the blue half.
    auto p = [&](int x, int y) {
      return last->likelihood.at<float>(y - last->search.y, x - last->search.x);
    };
    return std::make_tuple(p(target.x + 10, target.y + 10), p(target.x + 10, target.y + 30),
                           with_distractor);
  };
  tr::BoxTrackResult last;
  const auto [red_on, blue_on, frames_on] = run(0.5, &last);
  EXPECT_GT(tr::boxIou(last.box, target), 0.5);
  const auto [red_off, blue_off, frames_off] = run(0.0, &last);
  std::printf("P(O | red) %.3f, P(O | blue) %.3f with distractors (%d frames with the block), "
              "%.3f / %.3f without\n",
              red_on, blue_on, frames_on, red_off, blue_off);
  EXPECT_GE(frames_on, 20);
  EXPECT_EQ(frames_off, 0);
  EXPECT_LT(red_on, blue_on - 0.1);
  EXPECT_LT(red_on, red_off - 0.05);
}
