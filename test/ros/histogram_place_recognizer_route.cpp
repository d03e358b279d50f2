// rostest: histogram_place_recognizer over a route database (train_places --route) follows another
// drive along the route, and finds it again after a kidnap without a restart
// (histogram_place_recognizer_route.test).
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <cmath>
#include <cstdio>
#include <mutex>
#include <vector>

#include "adaptive_perception/PlaceRecognition.h"

namespace ap = adaptive_perception;

namespace {

struct Answer {
  int truth = 0;  // the query image's index on the route (1 Hz: its second since the drive began)
  int frame = -1;
  double confidence = 0.0;
};

// The share of `answers` from index `from` on within `tolerance` images of the truth.
double shareRight(const std::vector<Answer>& answers, std::size_t from, int tolerance) {
  int right = 0, n = 0;
  for (std::size_t i = from; i < answers.size(); ++i, ++n)
    right += std::abs(answers[i].frame - answers[i].truth) <= tolerance;
  return n ? static_cast<double>(right) / n : 0.0;
}

TEST(HistogramPlaceRecognizerRoute, FollowsTheRouteAndRecoversFromAKidnap) {
  ros::NodeHandle nh, p("~");
  const int tolerance = p.param("tolerance_frames", 2);
  const int settle = p.param("settle_frames", 15);
  const double min_share = p.param("min_share_right", 0.9);
  std::mutex mutex;
  std::string phase;
  double t0 = -1.0;
  std::vector<Answer> before, after;
  ros::Subscriber phase_sub = nh.subscribe<std_msgs::String>(
      "test_phase", 10, [&](const std_msgs::StringConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        phase = m->data;
      });
  ros::Subscriber place_sub = nh.subscribe<ap::PlaceRecognition>(
      "place", 1000, [&](const ap::PlaceRecognitionConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        if (phase != "test" && phase != "kidnap") return;
        const double t = m->header.stamp.toSec();
        if (t0 < 0.0) t0 = t;  // the first query image is the drive's first
        Answer a;
        a.truth = static_cast<int>(std::lround(t - t0));
        a.frame = m->route_frame;
        a.confidence = m->filtered_confidence;
        (phase == "test" ? before : after).push_back(a);
      });
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(240.0);
  while (ros::WallTime::now() < deadline) {
    {
      std::lock_guard<std::mutex> l(mutex);
      if (phase == "done") break;
    }
    ros::WallDuration(0.2).sleep();
  }
  std::lock_guard<std::mutex> l(mutex);
  ASSERT_EQ(phase, "done") << "the player did not finish";
  ASSERT_GE(before.size(), 140u);
  ASSERT_GE(after.size(), 140u);
  ASSERT_GE(after.front().truth, 295) << "the second part starts 300 s into the drive";
  // The route filter answers (a route database), from the first image.
  for (const Answer& a : before) ASSERT_GE(a.frame, 0);
  // Where the first answer after the kidnap was, and how long the filter took to follow.
  int recovered = -1;
  for (std::size_t i = 0; i < after.size() && recovered < 0; ++i)
    if (std::abs(after[i].frame - after[i].truth) <= tolerance) recovered = static_cast<int>(i);
  double conf_right = 0.0, conf_wrong = 0.0;
  int n_right = 0, n_wrong = 0;
  for (const auto* part : {&before, &after})
    for (const Answer& a : *part) {
      const bool right = std::abs(a.frame - a.truth) <= tolerance;
      (right ? conf_right : conf_wrong) += a.confidence;
      (right ? n_right : n_wrong) += 1;
    }
  std::printf(
      "histogram_place_recognizer_route: before=%zu right_after_settling=%.3f kidnap_first=%d "
      "(truth %d) recovered_after=%d right_after_recovery=%.3f mean_mass_right=%.3f "
      "mean_mass_wrong=%.3f\n",
      before.size(), shareRight(before, settle, tolerance), after.front().frame,
      after.front().truth, recovered, shareRight(after, settle, tolerance),
      n_right ? conf_right / n_right : 0.0, n_wrong ? conf_wrong / n_wrong : 0.0);
  EXPECT_GE(shareRight(before, settle, tolerance), min_share);
  EXPECT_GE(recovered, 0) << "never found again after the kidnap";
  EXPECT_LE(recovered, settle);
  EXPECT_GE(shareRight(after, settle, tolerance), min_share);
  if (n_wrong > 0) {
    EXPECT_GT(conf_right / n_right, conf_wrong / n_wrong)
        << "the posterior mass must mean something";
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "histogram_place_recognizer_route");
  return RUN_ALL_TESTS();
}
