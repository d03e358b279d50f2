// SequenceMatcher against a brute-force evaluation of its definition, a hand-worked enhancement,
// and a route whose single frames are ambiguous but whose sequence is not.
#include "adaptive_perception/places/sequence_matcher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace places = adaptive_perception::places;

namespace {

TEST(SequenceMatcher, EnhancementByHand) {
  places::SequenceMatcherConfig c;
  c.contrast_window_frames = 3;
  const places::SequenceMatcher m(c);
  // Windows: j=0 -> [0,3) = {1,2,6}; j=1 -> [0,3); j=2 -> [1,4) = {2,6,1}; j=3 -> [1,4).
  const std::vector<float> e = m.enhance({1.0f, 2.0f, 6.0f, 1.0f});
  const double mean = 3.0, sd = std::sqrt((4.0 + 1.0 + 9.0) / 3.0);
  EXPECT_NEAR(e[0], (1.0 - mean) / sd, 1e-5);
  EXPECT_NEAR(e[1], (2.0 - mean) / sd, 1e-5);
  EXPECT_NEAR(e[2], (6.0 - mean) / sd, 1e-5);
  EXPECT_NEAR(e[3], (1.0 - mean) / sd, 1e-5);
  // Equal distances have no contrast: 0, not a division by zero.
  for (float v : m.enhance({4.0f, 4.0f, 4.0f})) EXPECT_NEAR(v, 0.0f, 1e-6);
}

TEST(SequenceMatcher, AgreesWithBruteForce) {
  places::SequenceMatcherConfig c;
  c.sequence_frames = 6;
  c.min_velocity = 0.5;
  c.max_velocity = 2.0;
  c.velocity_steps = 4;
  c.contrast_window_frames = 7;
  places::SequenceMatcher m(c);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 10.0f);
  const int n = 40;
  std::vector<std::vector<float>> enhanced;  // all queries so far, oldest first
  for (int t = 0; t < 15; ++t) {
    std::vector<float> d(n);
    for (float& x : d) x = u(rng);
    enhanced.push_back(m.enhance(d));
    const std::vector<float> got = m.add(d);
    const int len = std::min<int>(c.sequence_frames, t + 1);
    for (int j = 0; j < n; ++j) {
      double best = std::numeric_limits<double>::infinity();
      for (int vi = 0; vi < c.velocity_steps; ++vi) {
        const double v = c.min_velocity * std::pow(c.max_velocity / c.min_velocity, vi / 3.0);
        double s = 0.0;
        for (int k = 0; k < len; ++k) {
          const long r = j - std::lround(v * k);
          if (r >= 0) s += enhanced[t - k][r];
        }
        best = std::min(best, s / len);
      }
      ASSERT_NEAR(got[j], best, 1e-4) << "query " << t << " reference " << j;
    }
  }
  EXPECT_EQ(m.queries(), 15);
}

TEST(SequenceMatcher, SequenceResolvesWhatSingleFramesCannot) {
  // 100 references; query t truly matches reference 20 + t. Each single frame is noisy and a
  // decoy reference 70 is always a little better than the truth; the decoy does not move along.
  places::SequenceMatcherConfig c;
  c.min_velocity = 1.0;
  c.max_velocity = 1.0;
  c.velocity_steps = 1;
  places::SequenceMatcher m(c);
  std::mt19937 rng(7);
  std::normal_distribution<float> noise(0.0f, 0.3f);
  int single_right = 0;
  for (int t = 0; t < 30; ++t) {
    std::vector<float> d(100);
    for (float& x : d) x = 5.0f + noise(rng);
    d[20 + t] = 3.0f;
    d[70] = 2.5f;
    single_right += std::min_element(d.begin(), d.end()) - d.begin() == 20 + t;
    const std::vector<float>& s = m.add(d);
    if (t >= 3) {
      EXPECT_EQ(std::min_element(s.begin(), s.end()) - s.begin(), 20 + t) << t;
    }
  }
  EXPECT_EQ(single_right, 0);
  m.reset();
  EXPECT_EQ(m.queries(), 0);
}

TEST(SequenceMatcher, DefaultsFollowAQueryDrivenAtAnotherSpeed) {
  // 400 references; query t truly matches reference 10 + floor(speed t), for speeds between half
  // and twice the reference's that lie on none of the searched velocities exactly. Each single
  // frame is noisy and its truth farther than a fixed decoy: single frames almost never find the
  // truth; with the defaults the trajectory search does, once a whole sequence has been seen.
  for (const double speed : {0.55, 0.83, 1.37, 1.93}) {
    places::SequenceMatcher m;  // defaults
    const int len = m.config().sequence_frames;
    std::mt19937 rng(11);
    std::normal_distribution<float> noise(0.0f, 0.3f);
    int single_right = 0, sequence_right = 0, scored = 0;
    for (int t = 0; 10 + speed * t < 390; ++t) {
      const int truth = 10 + static_cast<int>(std::floor(speed * t));
      std::vector<float> d(400);
      for (float& x : d) x = 5.0f + noise(rng);
      d[truth] = 4.0f;
      d[200] = 3.5f;
      single_right += std::min_element(d.begin(), d.end()) - d.begin() == truth;
      const std::vector<float>& s = m.add(d);
      if (t + 1 < len) continue;
      ++scored;
      const long got = std::min_element(s.begin(), s.end()) - s.begin();
      // Within one query frame's worth of references.
      sequence_right += std::abs(got - truth) <= std::max(1.0, std::ceil(speed));
    }
    EXPECT_LT(single_right, scored / 20) << speed;
    EXPECT_EQ(sequence_right, scored) << "speed " << speed;
  }
}

TEST(SequenceMatcher, RejectsBadInput) {
  places::SequenceMatcher m;
  EXPECT_THROW(m.add({}), std::invalid_argument);
  m.add({1.0f, 2.0f, 3.0f});
  EXPECT_THROW(m.add({1.0f, 2.0f}), std::invalid_argument);
  EXPECT_THROW(m.add({1.0f, std::nanf(""), 3.0f}), std::invalid_argument);
  places::SequenceMatcherConfig c;
  c.max_velocity = 0.4;  // below min_velocity
  EXPECT_THROW(places::SequenceMatcher{c}, std::invalid_argument);
  c = {};
  c.sequence_frames = 0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
