// PlaceRecognizer: the sliding window of eqs. (6)-(7), the auto choice of space / method, and the
// filter's use of the chosen node distances.
#include "adaptive_perception/places/place_recognizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include <opencv2/imgproc.hpp>

using namespace adaptive_perception::places;

namespace {
// Two spaces (rgb, hsv) over 2 bins: band 0 = (p, 1 - p) in rgb, (q, 1 - q) in hsv.
ImageHistograms hist(float p, float q) {
  ImageHistograms h;
  h.bins = 2;
  h.spaces[0] = {p, 1 - p, 1, 0, 1, 0};
  h.spaces[4] = {q, 1 - q, 1, 0, 1, 0};
  return h;
}
PlaceIndex twoPlaces() {
  PlaceIndex index(2);
  index.addPlace("a");
  index.addPlace("b");
  index.addImage(0, hist(1.0f, 1.0f));
  index.addImage(1, hist(0.0f, 0.0f));
  return index;
}
}  // namespace

TEST(PlaceRecognizer, WindowCombinesTheLastImages) {
  PlaceRecognizerConfig cfg;
  cfg.cue = "histogram";
  cfg.color_space = "rgb";
  cfg.method = "ks";
  cfg.window = 3;
  cfg.use_filter = false;
  PlaceRecognizer r(cfg);
  r.setDatabase(twoPlaces(), {{1}, {0}});
  EXPECT_EQ(r.spaces(), std::vector<int>{0});
  EXPECT_EQ(r.add(hist(0.9f, 0)).recognition.place, 0);
  EXPECT_EQ(r.add(hist(0.8f, 0)).recognition.place, 0);
  // Third image votes b; the window (0.9, 0.8, 0.1) still says a with 2/3.
  PlaceResult x = r.add(hist(0.1f, 0));
  EXPECT_EQ(x.recognition.place, 0);
  EXPECT_NEAR(x.recognition.confidence, 2.0 / 3, 1e-12);
  EXPECT_EQ(x.images, 3);
  // Two more b images push the a images out of the window of 3.
  r.add(hist(0.2f, 0));
  x = r.add(hist(0.0f, 0));
  EXPECT_EQ(x.recognition.place, 1);
  EXPECT_NEAR(x.recognition.confidence, 1.0, 1e-12);
  EXPECT_TRUE(x.belief.empty());
  r.reset();
  EXPECT_EQ(r.add(hist(0.9f, 0)).images, 1);
}

TEST(PlaceRecognizer, AutoPicksTheMostConfidentSpace) {
  // rgb is ambiguous (p = 0.5: a tie, first place wins, margin 0), hsv clearly says b.
  PlaceRecognizerConfig cfg;
  cfg.cue = "histogram";
  cfg.window = 2;
  cfg.use_filter = true;
  PlaceRecognizer r(cfg);
  r.setDatabase(twoPlaces(), {{1}, {0}});
  EXPECT_EQ(r.spaces(), (std::vector<int>{0, 4}));
  r.add(hist(0.5f, 0.1f));
  const PlaceResult x = r.add(hist(0.5f, 0.05f));
  EXPECT_EQ(x.recognition.space, 4);
  EXPECT_EQ(x.recognition.place, 1);
  ASSERT_EQ(x.belief.size(), 2u);
  EXPECT_EQ(x.filtered_place, 1);
  EXPECT_GT(x.belief[1], 0.9);
}

TEST(PlaceRecognizer, RefusesBadConfigAndEmptyDatabase) {
  PlaceRecognizerConfig bad;
  bad.color_space = "lab";
  EXPECT_THROW(PlaceRecognizer{bad}, std::invalid_argument);
  bad = {};
  bad.window = 0;
  EXPECT_THROW(PlaceRecognizer{bad}, std::invalid_argument);
  bad = {};
  bad.cue = "sift";
  EXPECT_THROW(PlaceRecognizer{bad}, std::invalid_argument);
  PlaceRecognizerConfig cfg;
  cfg.cue = "histogram";
  cfg.color_space = "hsi";
  PlaceRecognizer r(cfg);
  EXPECT_THROW(r.setDatabase(twoPlaces(), {{1}, {0}}), std::invalid_argument);  // no hsi
  PlaceRecognizer empty;
  EXPECT_THROW(empty.add(hist(0.5f, 0.5f)), std::logic_error);
  // The default (fused) cue on a database without whole-image descriptors.
  PlaceRecognizer fused;
  EXPECT_THROW(fused.setDatabase(twoPlaces(), {{1}, {0}}), std::invalid_argument);
}

namespace {
cv::Mat texture(int seed) {
  cv::Mat img(96, 128, CV_8UC3);
  cv::RNG rng(seed);
  rng.fill(img, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(img, img, cv::Size(0, 0), 2.0);
  cv::normalize(img, img, 40, 200, cv::NORM_MINMAX);
  return img;
}
}  // namespace

TEST(PlaceRecognizer, FusedCueFindsThePlaceOfTheNearestTrainingImage) {
  // Place a: views 0 and 1; place b: views 2 and 3. The query is view 3 under half the light.
  const PlaceIndex hist_index = twoPlaces();
  PlaceDescriptorIndex desc(hist_index.placeNames());
  const GlobalDescriptorConfig dc;
  for (int v = 0; v < 4; ++v) desc.addImage(v < 2 ? 0 : 1, computeDescriptors(texture(v), dc));
  PlaceRecognizerConfig cfg;
  cfg.window = 1;
  PlaceRecognizer r(cfg);
  ASSERT_TRUE(r.usesDescriptors());
  // twoPlaces() has one histogram image per place; the descriptors cover at least as many.
  r.setDatabase(hist_index, {{1}, {0}}, desc);
  cv::Mat dim;
  texture(3).convertTo(dim, -1, 0.5, 0.0);
  const ImageDescriptors q = computeDescriptors(dim, dc);
  const PlaceResult x = r.add(hist(0.5f, 0.5f), &q);
  EXPECT_EQ(x.cue, "fused");
  EXPECT_EQ(x.recognition.place, 1);
  EXPECT_EQ(x.recognition.space, -1);
  EXPECT_EQ(x.recognition.total_distances[1], 0.0);  // the nearest image of all
  EXPECT_GT(x.recognition.total_distances[0], 0.0);
  EXPECT_EQ(x.filtered_place, 1);
  EXPECT_THROW(r.add(hist(0.5f, 0.5f)), std::invalid_argument);  // no descriptors given
}

TEST(PlaceRecognizer, SequenceJoinsTheFilterOverADrive) {
  // A training drive of 24 views, six per place (a, b, c, d, adjacent in that order), driven
  // again under half the light. With use_sequence the filter also observes the sequence matcher,
  // whose best place is reported; without, it is not run.
  PlaceIndex index(2);
  for (const char* n : {"a", "b", "c", "d"}) index.addPlace(n);
  PlaceDescriptorIndex desc(index.placeNames());
  const GlobalDescriptorConfig dc;
  for (int v = 0; v < 24; ++v) {
    index.addImage(v / 6, hist(0.5f, 0.5f));
    desc.addImage(v / 6, computeDescriptors(texture(50 + v), dc));
  }
  const std::vector<std::vector<int>> chain = {{1}, {0, 2}, {1, 3}, {2}};
  for (bool use : {false, true}) {
    PlaceRecognizerConfig cfg;
    cfg.use_sequence = use;
    PlaceRecognizer r(cfg);
    r.setDatabase(index, chain, desc);
    int sequence_right = 0, filter_right = 0;
    for (int v = 0; v < 24; ++v) {
      cv::Mat dim;
      texture(50 + v).convertTo(dim, -1, 0.5, 0.0);
      const ImageDescriptors q = computeDescriptors(dim, dc);
      const PlaceResult x = r.add(hist(0.5f, 0.5f), &q);
      ASSERT_GE(x.filtered_place, 0);
      EXPECT_DOUBLE_EQ(x.filtered_confidence, x.belief[x.filtered_place]);
      if (!use) {
        EXPECT_EQ(x.sequence_place, -1);
      } else {
        sequence_right += x.sequence_place == v / 6;
      }
      filter_right += x.filtered_place == v / 6;
    }
    EXPECT_FALSE(r.usesRoute());  // six images a place: not one drive
    if (use) {
      EXPECT_EQ(sequence_right, 24);
    }
    EXPECT_GE(filter_right, 22) << (use ? "with" : "without") << " the sequence";
  }
}

TEST(PlaceRecognizer, RouteFilterAnswersOverOneDriveAndFollowsAKidnap) {
  // A reference drive of 30 views, each its own place, joined in the order stored (as
  // evaluate_places --database stores a traversal: names frame_N, so the index's name order is not
  // the drive's). Driven again under half the light: views 0-14, then carried to view 25.
  const int n = 30;
  PlaceIndex index(2);
  std::vector<std::string> names;
  for (int v = 0; v < n; ++v) names.push_back("frame_" + std::to_string(v + 1));
  std::vector<std::string> sorted = names;
  std::sort(sorted.begin(), sorted.end());
  for (const std::string& name : sorted) index.addPlace(name);
  auto placeOf = [&](int v) {
    return static_cast<int>(std::find(sorted.begin(), sorted.end(), names[v]) - sorted.begin());
  };
  PlaceDescriptorIndex desc(index.placeNames());
  const GlobalDescriptorConfig dc;
  std::vector<std::vector<int>> adjacency(n);
  for (int v = 0; v < n; ++v) {
    index.addImage(placeOf(v), hist(0.5f, 0.5f));
    desc.addImage(placeOf(v), computeDescriptors(texture(100 + v), dc));
    if (v > 0) {
      adjacency[placeOf(v)].push_back(placeOf(v - 1));
      adjacency[placeOf(v - 1)].push_back(placeOf(v));
    }
  }
  PlaceRecognizerConfig off;
  off.use_route = false;
  PlaceRecognizer without(off);
  without.setDatabase(index, adjacency, desc);
  EXPECT_FALSE(without.usesRoute());
  PlaceRecognizer r;
  r.setDatabase(index, adjacency, desc);
  ASSERT_TRUE(r.usesRoute());
  std::vector<int> drive;
  for (int v = 0; v < 15; ++v) drive.push_back(v);
  for (int v = 25; v < n; ++v) drive.push_back(v);
  int right = 0;
  for (size_t t = 0; t < drive.size(); ++t) {
    cv::Mat dim;
    texture(100 + drive[t]).convertTo(dim, -1, 0.5, 0.0);
    const ImageDescriptors q = computeDescriptors(dim, dc);
    const PlaceResult x = r.add(hist(0.5f, 0.5f), &q);
    ASSERT_GE(x.route_frame, 0);
    EXPECT_EQ(x.filtered_place, placeOf(x.route_frame));
    EXPECT_GT(x.filtered_confidence, 0.0);
    EXPECT_LE(x.filtered_confidence, 1.0);
    double total = 0.0;
    for (double b : x.belief) total += b;
    EXPECT_NEAR(total, 1.0, 1e-9);
    right += x.route_frame == drive[t];
    if (t == 0) {
      EXPECT_EQ(x.route_frame, 0);  // the first answer is the single image's
    }
    if (t >= 17) {
      EXPECT_EQ(x.route_frame, drive[t]) << "query " << t << " after the kidnap";
    }
  }
  EXPECT_GE(right, 18);
}
