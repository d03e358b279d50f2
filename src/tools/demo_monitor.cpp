// demo_monitor: a ROS node for the demo and for people replaying a bag: counts what arrives and,
// when it shuts down (the bag ended), prints one summary line
//   demo_monitor: bag=NAME frames=N image_hz=F mean_luma=Y truth_path_m=D map_odom_tf=K
//   field_markers=M classified_frames=C color_rate=R localizer_final_error_m=E   (camera bags)
//   demo_monitor: bag=NAME scans=N line_messages=L segments_per_scan=S ... slam_final_error_m=E
//   demo_monitor: bag=NAME rooms=N room_rate=R        (appearance_localizer on an indoor bag)
//   demo_monitor: bag=NAME tracked_frames=N success_rate=R   (condensation_tracker, IoU >= 0.5)
// (-1: not measured). Parameters: ~name (string, label of the run), ~map_frame and ~odom_frame
// (strings, default map and odom: the map -> odom transform that map_odom_tf counts). Subscribed: camera/image_raw,
// camera/labels, color_estimator/classified, ground_truth/pose, field_map, tf, scan, lines,
// rbpf_localizer/pose, ekf_slam_mapper/pose, ground_truth/place, appearance_localizer/room,
// ground_truth/box, tracked_object.
#include <geometry_msgs/PolygonStamped.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/PlaceRecognition.h"
#include "adaptive_perception/TrackedObject.h"
#include "adaptive_perception/ros/msg_conversion.h"
#include "adaptive_perception/ros/topics.h"

namespace T = adaptive_perception::ros_topics;

// Classification rate of color_estimator against the bag's true labels, over the map colours 0..4.
struct Rate {
  std::map<ros::Time, sensor_msgs::ImageConstPtr> truth;
  long correct = 0, total = 0, frames = 0;
  void score(const sensor_msgs::Image& truth_img, const sensor_msgs::Image& classified) {
    if (truth_img.data.size() != classified.data.size()) return;
    for (size_t i = 0; i < truth_img.data.size(); ++i) {
      if (truth_img.data[i] > 4) continue;
      ++total;
      correct += truth_img.data[i] == classified.data[i];
    }
    ++frames;
  }
};

struct Counts {
  long frames = 0, bad_frames = 0, map_odom = 0, markers = 0;
  double luma_sum = 0.0, path_m = 0.0;
  ros::Time first, last;
  bool have_pose = false;
  double px = 0, py = 0;
};

int main(int argc, char** argv) {
  ros::init(argc, argv, "demo_monitor");
  ros::NodeHandle nh, pnh("~");
  const std::string name = pnh.param<std::string>("name", "run");
  const std::string map_frame = pnh.param<std::string>("map_frame", T::kMapFrame);
  const std::string odom_frame = pnh.param<std::string>("odom_frame", T::kOdomFrame);
  Counts c;
  auto image_sub = nh.subscribe<sensor_msgs::Image>(
      T::kCameraImage, 5, [&](const sensor_msgs::ImageConstPtr& m) {
        try {
          const cv::Mat yuv = adaptive_perception::ros_conv::imageToYuv(*m);
          c.luma_sum += cv::mean(yuv)[0];
          if (c.frames == 0) c.first = m->header.stamp;
          c.last = m->header.stamp;
          ++c.frames;
        } catch (const std::exception& e) {
          ++c.bad_frames;
          ROS_WARN_THROTTLE(5.0, "demo_monitor: %s", e.what());
        }
      });
  // Estimates of the localizer and of the SLAM mapper, scored at the end against the truth nearest
  // in time to their last pose.
  std::map<ros::Time, std::pair<double, double>> truth;
  std::optional<geometry_msgs::PoseWithCovarianceStamped> last_rbpf, last_slam;
  auto rbpf_sub = nh.subscribe<geometry_msgs::PoseWithCovarianceStamped>(
      "rbpf_localizer/pose", 5,
      [&](const geometry_msgs::PoseWithCovarianceStampedConstPtr& m) { last_rbpf = *m; });
  auto slam_sub = nh.subscribe<geometry_msgs::PoseWithCovarianceStamped>(
      "ekf_slam_mapper/pose", 5,
      [&](const geometry_msgs::PoseWithCovarianceStampedConstPtr& m) { last_slam = *m; });
  auto finalError = [&](const std::optional<geometry_msgs::PoseWithCovarianceStamped>& e) {
    if (!e || truth.empty()) return -1.0;
    auto t = truth.lower_bound(e->header.stamp);
    if (t == truth.end()) t = std::prev(t);
    return std::hypot(e->pose.pose.position.x - t->second.first,
                      e->pose.pose.position.y - t->second.second);
  };
  auto truth_sub = nh.subscribe<geometry_msgs::PoseStamped>(
      T::kGroundTruthPose, 50, [&](const geometry_msgs::PoseStampedConstPtr& m) {
        truth[m->header.stamp] = {m->pose.position.x, m->pose.position.y};
        if (c.have_pose)
          c.path_m += std::hypot(m->pose.position.x - c.px, m->pose.position.y - c.py);
        c.px = m->pose.position.x;
        c.py = m->pose.position.y;
        c.have_pose = true;
      });
  auto tf_sub =
      nh.subscribe<tf2_msgs::TFMessage>("/tf", 100, [&](const tf2_msgs::TFMessageConstPtr& m) {
        for (const auto& t : m->transforms)
          if (t.header.frame_id == map_frame && t.child_frame_id == odom_frame) ++c.map_odom;
      });
  auto map_sub = nh.subscribe<visualization_msgs::MarkerArray>(
      T::kFieldMap, 1,
      [&](const visualization_msgs::MarkerArrayConstPtr& m) { c.markers = m->markers.size(); });
  Rate rate;
  std::map<ros::Time, sensor_msgs::ImageConstPtr> classified;
  auto labels_sub = nh.subscribe<sensor_msgs::Image>(T::kCameraLabels, 20,
                                                     [&](const sensor_msgs::ImageConstPtr& m) {
                                                       auto it = classified.find(m->header.stamp);
                                                       if (it != classified.end()) {
                                                         rate.score(*m, *it->second);
                                                         classified.erase(it);
                                                       } else {
                                                         rate.truth[m->header.stamp] = m;
                                                       }
                                                     });
  auto classified_sub = nh.subscribe<sensor_msgs::Image>(
      "color_estimator/classified", 20, [&](const sensor_msgs::ImageConstPtr& m) {
        auto it = rate.truth.find(m->header.stamp);
        if (it != rate.truth.end()) {
          rate.score(*it->second, *m);
          rate.truth.erase(it);
        } else {
          classified[m->header.stamp] = m;
        }
      });
  long scans = 0, line_msgs = 0, segments = 0;
  auto scan_sub = nh.subscribe<sensor_msgs::LaserScan>(
      T::kScan, 50, [&](const sensor_msgs::LaserScanConstPtr&) { ++scans; });
  auto lines_sub = nh.subscribe<adaptive_perception::LineSegmentArray>(
      "lines", 50, [&](const adaptive_perception::LineSegmentArrayConstPtr& m) {
        ++line_msgs;
        segments += static_cast<long>(m->segments.size());
      });
  // Rooms: each appearance_localizer result against the true place when it arrives (the place has
  // no stamp; the robot stays in a room for many images). Images outside every place are skipped.
  std::string true_place;
  long rooms = 0, rooms_right = 0;
  auto place_sub = nh.subscribe<std_msgs::String>(
      T::kGroundTruthPlace, 10, [&](const std_msgs::StringConstPtr& m) { true_place = m->data; });
  auto room_sub = nh.subscribe<adaptive_perception::PlaceRecognition>(
      "appearance_localizer/room", 20, [&](const adaptive_perception::PlaceRecognitionConstPtr& m) {
        if (true_place.empty() || true_place == "none") return;
        ++rooms;
        rooms_right += m->place == true_place;
      });
  // Tracking: the tracker's box against the true box of the same image (IoU >= 0.5 is a success).
  std::map<ros::Time, cv::Rect2d> true_boxes, tracked_boxes;
  long tracked = 0, tracked_right = 0;
  auto score_box = [&](const cv::Rect2d& a, const cv::Rect2d& b) {
    const double inter = (a & b).area(), uni = a.area() + b.area() - inter;
    ++tracked;
    tracked_right += uni > 0.0 && inter / uni >= 0.5;
  };
  auto box_sub = nh.subscribe<geometry_msgs::PolygonStamped>(
      T::kGroundTruthBox, 20, [&](const geometry_msgs::PolygonStampedConstPtr& m) {
        const cv::Rect2d box = adaptive_perception::ros_conv::polygonBox(m->polygon);
        auto it = tracked_boxes.find(m->header.stamp);
        if (it != tracked_boxes.end()) {
          score_box(box, it->second);
          tracked_boxes.erase(it);
        } else {
          true_boxes[m->header.stamp] = box;
        }
      });
  auto tracked_sub = nh.subscribe<adaptive_perception::TrackedObject>(
      T::kTrackedObject, 20, [&](const adaptive_perception::TrackedObjectConstPtr& m) {
        const cv::Rect2d box(m->box.x_offset, m->box.y_offset, m->box.width, m->box.height);
        auto it = true_boxes.find(m->header.stamp);
        if (it != true_boxes.end()) {
          score_box(it->second, box);
          true_boxes.erase(it);
        } else {
          tracked_boxes[m->header.stamp] = box;
        }
      });
  ros::spin();
  if (rooms > 0) {
    std::printf("demo_monitor: bag=%s rooms=%ld room_rate=%.3f\n", name.c_str(), rooms,
                double(rooms_right) / rooms);
    std::fflush(stdout);
    return 0;
  }
  if (tracked > 0) {
    std::printf("demo_monitor: bag=%s tracked_frames=%ld success_rate=%.3f\n", name.c_str(),
                tracked, double(tracked_right) / tracked);
    std::fflush(stdout);
    return 0;
  }
  if (scans > 0) {
    std::printf(
        "demo_monitor: bag=%s scans=%ld line_messages=%ld segments_per_scan=%.2f truth_path_m=%.2f "
        "map_odom_tf=%ld slam_final_error_m=%.3f\n",
        name.c_str(), scans, line_msgs, line_msgs ? double(segments) / line_msgs : 0.0, c.path_m,
        c.map_odom, finalError(last_slam));
    std::fflush(stdout);
    return 0;
  }
  const double span = (c.last - c.first).toSec();
  std::printf(
      "demo_monitor: bag=%s frames=%ld bad_frames=%ld image_hz=%.2f mean_luma=%.1f "
      "truth_path_m=%.2f "
      "map_odom_tf=%ld field_markers=%ld classified_frames=%ld color_rate=%.3f "
      "localizer_final_error_m=%.3f\n",
      name.c_str(), c.frames, c.bad_frames, span > 0 ? (c.frames - 1) / span : 0.0,
      c.frames ? c.luma_sum / c.frames : 0.0, c.path_m, c.map_odom, c.markers, rate.frames,
      rate.total ? double(rate.correct) / rate.total : 0.0, finalError(last_rbpf));
  std::fflush(stdout);
  return 0;
}
