// Appearance MCL on scripted inputs: the training run's average step, heading-aware nearest frames,
// convergence and room by summed weight, stability, restricted then full re-initialisation,
// unknown-room detection, runs that do not depend on OpenCV's generator, and the odometry
// buffer and sync that give each image the pose at its stamp.
#include "adaptive_perception/localization/appearance_mcl.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "adaptive_perception/localization/odometry_buffer.h"
#include "adaptive_perception/math/angles.h"

using namespace adaptive_perception;
using localization::AppearanceMcl;
using localization::AppearanceMclConfig;
using localization::PosedFrame;

namespace {
// A corridor run: frames every 0.5 m along x from 0 to 20 m, heading +x; room 0 below x = 10,
// room 1 from there.
std::vector<PosedFrame> corridor() {
  std::vector<PosedFrame> f;
  for (int i = 0; i <= 40; ++i) f.push_back({math::SE2(0.5 * i, 0.0, 0.0), i * 0.5 < 10.0 ? 0 : 1});
  return f;
}
// The same corridor between two parallel ones 2 m to either side (frames 41-81 at y = -2 m, 82-122
// at y = +2 m) whose views the test's images never match, so that the images tell the lateral
// position as well as x (with one corridor alone nothing holds the particles' y, and whether a
// quarter of them wander past known_radius_m is chance).
std::vector<PosedFrame> threeCorridors() {
  std::vector<PosedFrame> f = corridor();
  for (double y : {-2.0, 2.0})
    for (int i = 0; i <= 40; ++i) f.push_back({math::SE2(0.5 * i, y, 0.0), i * 0.5 < 10.0 ? 0 : 1});
  return f;
}
// What the matcher would say of an image taken at x: the frame there 0.6, its neighbours 0.3.
std::vector<places::FrameMatch> seenAt(double x) {
  const int i = static_cast<int>(std::lround(x / 0.5));
  std::vector<places::FrameMatch> m;
  for (int k = i - 1; k <= i + 1; ++k)
    if (k >= 0 && k <= 40) m.push_back({k, k == i ? 0.6 : 0.3});
  return m;
}
}  // namespace

TEST(AppearanceMcl, AverageStepAndHeadingAwareNearestFrame) {
  AppearanceMcl mcl(corridor(), 2, {}, 1);
  EXPECT_NEAR(mcl.averageStep().x_m, 0.5, 1e-9);
  EXPECT_NEAR(mcl.averageStep().y_m, 0.0, 1e-9);
  std::vector<PosedFrame> two = {{math::SE2(1, 1, 0.0), 0}, {math::SE2(1, 1, M_PI), 1}};
  AppearanceMcl m2(two, 2, {}, 1);
  EXPECT_EQ(m2.nearestFrame(math::SE2(1.1, 1, 3.0)), 1);
  EXPECT_EQ(m2.nearestFrame(math::SE2(1.1, 1, 0.2)), 0);
  EXPECT_NEAR(m2.distanceToKnown(4, 5), 5.0, 1e-5);
}

TEST(AppearanceMcl, InitialPoseDrawsTheGivenGaussian) {
  // Monte Carlo check: 20,000 particles from a correlated covariance about a heading near +-pi
  // (the draws wrap); their mean and covariance against the given ones, within a few standard
  // errors (a variance's standard error with n draws is about sqrt(2 / n) of it: 1%).
  AppearanceMclConfig cfg;
  cfg.particles = 20000;
  AppearanceMcl mcl(corridor(), 2, cfg, 5);
  Eigen::Matrix3d cov;
  cov << 0.25, 0.05, 0.0, 0.05, 0.09, 0.01, 0.0, 0.01, 0.04;
  const math::SE2 mean(3.0, -1.0, 3.1);
  mcl.initGaussian(mean, cov);
  ASSERT_EQ(mcl.particles().size(), 20000u);
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> d;
  for (const math::SE2& p : mcl.particles()) {
    EXPECT_LE(std::abs(p.yaw_rad), M_PI + 1e-12);
    d.emplace_back(p.x_m - mean.x_m, p.y_m - mean.y_m, math::angleDiff(p.yaw_rad, mean.yaw_rad));
    m += d.back();
  }
  m /= d.size();
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (const auto& v : d) c += (v - m) * (v - m).transpose();
  c /= d.size() - 1;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(m[i], 0.0, 4.0 * std::sqrt(cov(i, i) / d.size())) << i;
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(c(i, j), cov(i, j),
                  4.0 * std::sqrt((cov(i, i) * cov(j, j) + cov(i, j) * cov(i, j)) / d.size()))
          << i << "," << j;
  }
  Eigen::Matrix3d not_spd = cov;
  not_spd(0, 0) = -1.0;
  EXPECT_THROW(mcl.initGaussian(mean, not_spd), std::invalid_argument);
  not_spd = cov;
  not_spd(1, 1) = std::nan("");
  EXPECT_THROW(mcl.initGaussian(mean, not_spd), std::invalid_argument);
}

TEST(AppearanceMcl, ConvergesBecomesStableThenReinitialisesWhenLost) {
  AppearanceMclConfig cfg;
  cfg.particles = 500;
  AppearanceMcl mcl(threeCorridors(), 2, cfg, 3);
  const math::SE2 step(0.5, 0.0, 0.0);
  localization::AppearanceEstimate e;
  double x = 2.0;
  bool was_stable = false;
  for (int k = 0; k < 20; ++k, x += 0.5) {
    e = mcl.step(step, seenAt(x));
    was_stable = was_stable || e.stable;
  }
  ASSERT_TRUE(e.stable);
  EXPECT_NEAR(e.pose.x_m, x - 0.5, 0.5);
  EXPECT_EQ(e.room, 1);  // x = 11.5: the second room
  EXPECT_FALSE(e.unknown_room);
  // Images that match nothing: unstable, "not classified", and re-initialised around the last
  // reliable pose first, over everything after full_reinit_after frames in a row.
  const math::SE2 reliable = e.pose;
  e = mcl.step(step, {});
  EXPECT_FALSE(e.stable);
  EXPECT_EQ(e.room, -1);
  EXPECT_TRUE(e.reinitialized);
  EXPECT_FALSE(e.full_reinit);
  const double radius = cfg.reinit_radius_m + cfg.reinit_radius_gain_m;
  for (const math::SE2& p : mcl.particles())
    EXPECT_LE(std::hypot(p.x_m - reliable.x_m, p.y_m - reliable.y_m), radius + 1e-9);
  bool full = false;
  for (int k = 1; k < cfg.full_reinit_after && !full; ++k) full = mcl.step(step, {}).full_reinit;
  EXPECT_TRUE(full);
  // After a full re-initialisation the particles cover the whole run again.
  double lo = 1e9, hi = -1e9;
  for (const math::SE2& p : mcl.particles()) {
    lo = std::min(lo, p.x_m);
    hi = std::max(hi, p.x_m);
  }
  EXPECT_LT(lo, 3.0);
  EXPECT_GT(hi, 17.0);
}

TEST(AppearanceMcl, UnknownRoomWhenAQuarterOfTheParticlesLeaveTheKnownPlaces) {
  AppearanceMclConfig cfg;
  cfg.particles = 100;
  AppearanceMcl mcl(corridor(), 2, cfg, 5);
  // 30 of 100 particles 5 m beside the corridor: unknown.
  std::vector<math::SE2> p;
  for (int i = 0; i < 100; ++i) p.emplace_back(5.0, i < 30 ? 5.0 : 0.0, 0.0);
  mcl.setParticles(p);
  auto e = mcl.step(math::SE2(0, 0, 0), seenAt(5.0));
  EXPECT_TRUE(e.unknown_room);
  EXPECT_EQ(e.room, -1);
  // 20 of 100: below the 25% rule.
  p.clear();
  for (int i = 0; i < 100; ++i) p.emplace_back(5.0, i < 20 ? 5.0 : 0.0, 0.0);
  mcl.setParticles(p);
  EXPECT_FALSE(mcl.step(math::SE2(0, 0, 0), seenAt(5.0)).unknown_room);
}

// The same seed gives the same particles whatever OpenCV's generator drew before (its kd-trees
// are built with their own seed), and building them leaves that generator as it was.
TEST(AppearanceMcl, TheSameRunWhateverOpenCvsGeneratorDrewBefore) {
  auto run = [] {
    AppearanceMcl mcl(corridor(), 2, {}, 3);
    for (double x = 2.0; x < 12.0; x += 0.5) mcl.step(math::SE2(0.5, 0.0, 0.0), seenAt(x));
    return mcl.particles();
  };
  const std::vector<math::SE2> first = run();
  cv::theRNG().next();
  const std::uint64_t before = cv::theRNG().state;
  const std::vector<math::SE2> second = run();
  EXPECT_EQ(cv::theRNG().state, before);
  ASSERT_EQ(first.size(), second.size());
  for (size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].x_m, second[i].x_m) << i;
    EXPECT_EQ(first[i].y_m, second[i].y_m) << i;
    EXPECT_EQ(first[i].yaw_rad, second[i].yaw_rad) << i;
  }
}

TEST(AppearanceMcl, RefusesBadConfiguration) {
  AppearanceMclConfig bad;
  bad.particles = 1;
  EXPECT_THROW(AppearanceMcl(corridor(), 2, bad, 1), std::invalid_argument);
  EXPECT_THROW(AppearanceMcl({}, 2, {}, 1), std::invalid_argument);
  EXPECT_THROW(AppearanceMcl({{math::SE2(0, 0, 0), 3}}, 2, {}, 1), std::invalid_argument);
}

// The odometry the appearance localizer moves its particles by, taken at each image's stamp.
TEST(OdometryBuffer, InterpolatesBetweenThePosesOnEitherSideOfTheStamp) {
  localization::OdometryBuffer b;  // max_age_s 1, restart_after_back_s 1
  EXPECT_FALSE(b.at(5.0));         // nothing kept
  EXPECT_FALSE(b.newest());
  b.add(1.0, math::SE2(1, 0, 3.0));
  b.add(1.4, math::SE2(3, 2, -3.0));      // the heading crosses +-pi: 0.283 rad the short way
  EXPECT_FALSE(b.at(0.9));                // every pose is newer than the image
  EXPECT_DOUBLE_EQ(b.at(1.0)->x_m, 1.0);  // at a stamp kept
  const math::SE2 q = *b.at(1.1);         // a quarter of the way
  EXPECT_NEAR(q.x_m, 1.5, 1e-12);
  EXPECT_NEAR(q.y_m, 0.5, 1e-12);
  EXPECT_NEAR(q.yaw_rad, 3.0 + 0.25 * (2 * M_PI - 6.0), 1e-12);
  EXPECT_DOUBLE_EQ(b.at(2.3)->x_m, 3.0);  // 0.9 s after the newest: the newest
  EXPECT_FALSE(b.at(2.5));                // 1.1 s after: a stalled source gives nothing
  EXPECT_DOUBLE_EQ(*b.newest(), 1.4);
}

TEST(OdometryBuffer, KeepsStampOrderAndStartsAgainWhenTimeGoesBack) {
  localization::OdometryBuffer b;
  b.add(10.0, math::SE2(1, 0, 0));
  b.add(10.4, math::SE2(5, 0, 0));
  b.add(10.2, math::SE2(9, 0, 0));  // 0.2 s older than the newest: a late message, put in place
  EXPECT_DOUBLE_EQ(b.at(10.1)->x_m, 5.0);  // between 10.0 (1) and 10.2 (9)
  b.add(10.2, math::SE2(3, 0, 0));         // the same stamp again replaces
  EXPECT_DOUBLE_EQ(b.at(10.2)->x_m, 3.0);
  EXPECT_EQ(b.size(), 3u);
  b.add(3.0, math::SE2(7, 0, 0));  // 7.4 s back: a looped log, the first pass's poses go
  EXPECT_EQ(b.size(), 1u);
  EXPECT_DOUBLE_EQ(*b.newest(), 3.0);
}

TEST(OdometryBuffer, ARestartDropsOnlyPosesFromBeforeTheJumpAndOldPosesAge) {
  localization::OdometryBuffer b;
  b.add(50.0, math::SE2(1, 0, 0));
  b.restartAt(49.5);  // the images went back 0.5 s: within restart_after_back_s, kept
  EXPECT_EQ(b.size(), 1u);
  b.restartAt(20.0);  // 30 s back: the poses are of the time before the jump
  EXPECT_EQ(b.size(), 0u);
  b.add(20.05, math::SE2(2, 0, 0));  // the new pass's odometry came before its first image
  b.restartAt(20.0);
  EXPECT_EQ(b.size(), 1u);
  localization::OdometryBuffer c(localization::OdometryBufferConfig{1.0, 1.0, 0.25});
  for (int i = 0; i < 5; ++i) c.add(0.1 * i, math::SE2(i, 0, 0));
  EXPECT_EQ(c.size(), 3u);  // 0.2, 0.3, 0.4: span_s 0.25 back from the newest
  EXPECT_FALSE(c.at(0.15));
}

TEST(OdometryBuffer, DoesNotBridgeAGapLongerThanItsMaxAge) {
  localization::OdometryBuffer b;  // max_age_s 1
  b.add(0.0, math::SE2(0, 0, 0));
  b.add(3.0, math::SE2(3, 0, 0));
  EXPECT_FALSE(b.at(1.5));  // 3 s between the poses on either side: the source stalled
  b.add(2.5, math::SE2(2, 0, 0));
  EXPECT_NEAR(b.at(2.75)->x_m, 2.5, 1e-12);
}

namespace {
using Sync = localization::OdometrySync<int>;
// Odometry at 20 Hz moving 1 m/s along x, images at 5 Hz on the same clock, delivered in the
// order `events` gives: 'i' the next image, 'o' the next odometry message. Returns every release
// as (image, x of its pose or -1).
std::vector<std::pair<int, double>> replay(const std::string& events) {
  Sync sync;
  std::vector<std::pair<int, double>> out;
  int image = 0, odom = 0;
  auto take = [&](std::vector<Sync::Release> r) {
    for (const auto& x : r) out.emplace_back(x.item, x.pose ? x.pose->x_m : -1.0);
  };
  for (char e : events) {
    if (e == 'i') {
      take(sync.image(0.2 * image, image));
      ++image;
    } else {
      take(sync.odometry(0.05 * odom, math::SE2(0.05 * odom, 0, 0)));
      ++odom;
    }
  }
  return out;
}
}  // namespace

TEST(OdometrySync, ImagesGetTheSameOdometryWhateverOrderTheStreamsArriveIn) {
  // For each image k (at odometry message 4k's stamp): in stamp order; the image before its own
  // odometry message; the image after the next message too. Then odometry past the last image.
  std::string in_order, images_first, odometry_late;
  for (int k = 0; k < 4; ++k) {
    in_order += "oiooo";
    images_first += "ioooo";
    odometry_late += "ooioo";
  }
  for (std::string* e : {&in_order, &images_first, &odometry_late}) *e += "o";
  const auto a = replay(in_order), b = replay(images_first), c = replay(odometry_late);
  ASSERT_EQ(a.size(), 4u);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a, c);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(a[k].first, k);
    EXPECT_NEAR(a[k].second, 0.2 * k, 1e-12);  // the pose at each image's own stamp
  }
}

TEST(OdometrySync, WithoutOdometryImagesGoAfterThreeAndWaitAgainWhenItComes) {
  Sync sync;
  EXPECT_TRUE(sync.image(0.0, 0).empty());  // held
  for (int k = 1; k <= 3; ++k) {
    const auto r = sync.image(0.2 * k, k);  // the held one goes, without odometry
    ASSERT_EQ(r.size(), k < 3 ? 1u : 2u);   // the third in a row: this one goes at once too
    EXPECT_EQ(r[0].item, k - 1);
    EXPECT_FALSE(r[0].pose);
  }
  EXPECT_FALSE(sync.matching());
  const auto now = sync.image(0.8, 4);  // released at once
  ASSERT_EQ(now.size(), 1u);
  EXPECT_EQ(now[0].item, 4);
  EXPECT_EQ(sync.unmatched(), 5);
  // Odometry comes and reaches the last image: images wait for it again.
  EXPECT_TRUE(sync.odometry(0.8, math::SE2(8, 0, 0)).empty());
  EXPECT_TRUE(sync.matching());
  EXPECT_TRUE(sync.image(1.0, 5).empty());
  const auto r = sync.odometry(1.0, math::SE2(10, 0, 0));
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].item, 5);
  EXPECT_NEAR(r[0].pose->x_m, 10.0, 1e-12);
}

TEST(OdometrySync, ARestartDropsTheHeldImageAndTheOdometryBeforeTheJump) {
  Sync sync;
  EXPECT_TRUE(sync.odometry(100.0, math::SE2(1, 0, 0)).empty());
  EXPECT_TRUE(sync.image(100.2, 0).empty());  // held
  sync.restart(10.0);                         // the log looped
  EXPECT_FALSE(sync.waiting());
  EXPECT_TRUE(sync.image(10.0, 1).empty());  // waits: the old pass's odometry is gone
  const auto r = sync.odometry(10.0, math::SE2(2, 0, 0));
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].item, 1);
  EXPECT_NEAR(r[0].pose->x_m, 2.0, 1e-12);
}
