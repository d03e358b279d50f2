// rostest: histogram_place_recognizer trained through its add_images service on one simulator run
// of the indoor building, then recognising the places of another run.
#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/String.h>
#include <std_srvs/Trigger.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <mutex>
#include <set>

#include "adaptive_perception/AddPlaceImages.h"
#include "adaptive_perception/PlaceRecognition.h"
#include "adaptive_perception/RemovePlace.h"
#include "adaptive_perception/SetPlaceAdjacency.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/params.h"
#include "adaptive_perception/sim/indoor_world.h"

namespace ap = adaptive_perception;

TEST(HistogramPlaceRecognizerSim, TrainsThroughTheServiceAndRecognisesAnotherRun) {
  ros::NodeHandle nh, p("~");
  const int per_place = p.param("images_per_place", 5);
  const double min_window = p.param("min_window_accuracy", 0.6);
  const double min_filter = p.param("min_filter_accuracy", 0.6);
  const int min_results = p.param("min_results", 450);
  // The fused cue's filter also observes the sequence matcher; the histogram cue has none.
  const bool expect_sequence = p.param("expect_sequence", false);
  const ap::sim::IndoorWorld world = ap::sim::IndoorWorld::loadYaml(
      ap::ros_params::resolvePackagePath("config/worlds/indoor_building.yaml"));

  std::mutex mutex;
  std::string phase;
  std::map<ros::Time, std::string> truth;  // test phase: place of the true pose at each stamp
  std::vector<ap::PlaceRecognition> results;
  std::set<std::string> requested;
  std::string collecting;
  int overlays = 0;
  ros::ServiceClient add =
      nh.serviceClient<ap::AddPlaceImages>("histogram_place_recognizer/add_images");
  auto phase_sub =
      nh.subscribe<std_msgs::String>("test_phase", 5, [&](const std_msgs::StringConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        phase = m->data;
      });
  auto label_sub = nh.subscribe<std_msgs::String>(
      "ground_truth/place", 100, [&](const std_msgs::StringConstPtr& m) {
        std::string place;
        {
          std::lock_guard<std::mutex> l(mutex);
          if (phase != "train" || m->data == "none" || requested.count(m->data)) return;
          place = m->data;
        }
        // Entering a place not trained yet: ask for its next images.
        ap::AddPlaceImages srv;
        srv.request.place = place;
        srv.request.count = per_place;
        if (add.call(srv) && srv.response.success) {
          std::lock_guard<std::mutex> l(mutex);
          requested.insert(place);
        }
      });
  auto pose_sub = nh.subscribe<geometry_msgs::PoseStamped>(
      "ground_truth/pose", 5000, [&](const geometry_msgs::PoseStampedConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        if (phase != "test") return;
        const int i = world.placeAt({m->pose.position.x, m->pose.position.y});
        truth[m->header.stamp] = i >= 0 ? world.places[i].name : "none";
      });
  auto place_sub =
      nh.subscribe<ap::PlaceRecognition>("place", 1000, [&](const ap::PlaceRecognitionConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        if (phase == "test") results.push_back(*m);
      });
  auto overlay_sub = nh.subscribe<sensor_msgs::Image>(
      "histogram_place_recognizer/overlay", 5, [&](const sensor_msgs::ImageConstPtr& m) {
        std::lock_guard<std::mutex> l(mutex);
        overlays += m->encoding == "bgr8" && m->width >= 480;
      });
  ros::AsyncSpinner spinner(3);
  spinner.start();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(280.0);
  while (ros::ok() && ros::WallTime::now() < deadline) {
    {
      std::lock_guard<std::mutex> l(mutex);
      if (phase == "done") break;
    }
    ros::WallDuration(0.2).sleep();
  }
  ASSERT_EQ(phase, "done") << "the player did not finish";
  ros::WallDuration(0.5).sleep();

  std::lock_guard<std::mutex> l(mutex);
  EXPECT_GE(requested.size(), 10u) << "places trained through add_images";
  ASSERT_GE(static_cast<int>(results.size()), min_results);
  int scored = 0, window_right = 0, filter_right = 0, with_sequence = 0;
  std::map<std::string, std::pair<int, int>> by_place;
  for (const auto& r : results) {
    const auto it = truth.find(r.header.stamp);
    if (it == truth.end() || it->second == "none") continue;
    ++scored;
    window_right += r.place == it->second;
    filter_right += r.filtered_place == it->second;
    by_place[it->second].first += r.place == it->second;
    by_place[it->second].second += 1;
    EXPECT_EQ(r.places.size(), r.distances.size());
    EXPECT_EQ(r.places.size(), r.belief.size());
    EXPECT_GE(r.confidence, 0.0);
    EXPECT_LE(r.confidence, 1.0);
    // The fused answer's confidence is the filter's belief in it.
    const auto f = std::find(r.places.begin(), r.places.end(), r.filtered_place);
    ASSERT_NE(f, r.places.end()) << "filtered_place '" << r.filtered_place << "'";
    EXPECT_DOUBLE_EQ(r.filtered_confidence, r.belief[f - r.places.begin()]);
    with_sequence += !r.sequence_place.empty();
  }
  if (expect_sequence)
    EXPECT_EQ(with_sequence, scored) << "every result carries the sequence matcher's place";
  else
    EXPECT_EQ(with_sequence, 0);
  for (const auto& [place, c] : by_place)
    std::printf("  %-20s window %d / %d\n", place.c_str(), c.first, c.second);
  ASSERT_GT(scored, min_results * 0.9);
  const double window_acc = static_cast<double>(window_right) / scored;
  const double filter_acc = static_cast<double>(filter_right) / scored;
  std::printf(
      "histogram_place_recognizer_sim: scored=%d window_accuracy=%.3f "
      "filter_accuracy=%.3f\n",
      scored, window_acc, filter_acc);
  EXPECT_GE(window_acc, min_window);
  EXPECT_GE(filter_acc, min_filter);
  EXPECT_GT(overlays, 0);

  // Services refuse bad requests with a message, and the node keeps running.
  ap::RemovePlace rm;
  rm.request.place = "nowhere";
  ASSERT_TRUE(ros::service::call("histogram_place_recognizer/remove_place", rm));
  EXPECT_FALSE(rm.response.success);
  ap::SetPlaceAdjacency adj;
  adj.request.place_a = "kitchen";
  adj.request.place_b = "nowhere";
  adj.request.connected = true;
  ASSERT_TRUE(ros::service::call("histogram_place_recognizer/set_adjacency", adj));
  EXPECT_FALSE(adj.response.success);
  EXPECT_NE(adj.response.message.find("nowhere"), std::string::npos) << adj.response.message;
  std_srvs::Trigger save;
  ASSERT_TRUE(ros::service::call("histogram_place_recognizer/save", save));
  EXPECT_TRUE(save.response.success) << save.response.message;
  std::string db;
  if (nh.getParam("histogram_place_recognizer/database", db)) std::remove(db.c_str());
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "histogram_place_recognizer_sim");
  return RUN_ALL_TESTS();
}
