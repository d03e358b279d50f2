// rostest harness: hostile input, then good input, for one node (test/ros/hostile_*.test).
//
// The test plays a bag itself (with /clock; the launch sets use_sim_time) so it controls every
// phase:
//   A      the bag at `rate`: the node's reference output;
//   hostile  malformed messages on the node's inputs (unsupported encodings, zero-size and
//            mismatched-step images, NaN / inf / negative ranges, zero-beam scans, frames with no
//            tf, stale stamps, non-finite line covariances, ...), all stamped after the bag's end;
//   storm  the bag again at `storm_factor` x `rate` (time jumps backwards at its start): every
//          output's latency (wall time from the input with its stamp to the output) must stay
//          bounded;
//   B      the bag once more at `rate` (time jumps backwards again): the output must be correct,
//          judged by `compare` against A or against the bag's ground truth.
//          With jitter_s > 0, every trigger input is re-sent right after it, jitter_s seconds
//          older (a second publisher): the node must drop those, not answer or restart on them
//          (its outputs' stamps never go back), and pass B is still judged by `compare`.
//   stall  (when stall_service is set) the clock stops; one input arrives whose frame has no tf
//          and will never get one; the node's service must still answer within
//          stall_answer_timeout_s of wall time (a tf wait measured in sim time never ends).
// With bad_reconfigure set, the node's dynamic_reconfigure server is given each bad setting before
// the storm (every value in its reply must be finite: a refused setting is not taken), and its
// original settings back before pass B; the storm and pass B then show it survived them.
// At the end the node must still answer over XML-RPC (a crashed node stays registered).
//
// Parameters (private):
//   bag (string)                 the good input, waited for up to startup_timeout_s (60) when a
//                                launch node makes it (remove_bag_dir: delete its folder at the
//                                end); or `bag_command` (string) makes it first: a shell command
//                                run with $BAG set to a temporary path
//   replay_topics (string list)  bag topics to publish (tf_static latched); /clock is added
//   trigger_topic (string)       the input whose stamp an output carries (latency, output fraction)
//   output_topic (string)        the output watched; its message must start with a Header
//   node (string)                the node's name, checked with the master at the end
//   image_topic / scan_topic / lines_topic / pose_topic (string, "" = none): where hostile input
//                                goes; pose_topic takes PoseWithCovarianceStamped in pose_frame
//                                (string, "map") that the node must refuse (initialpose,
//                                external_pose)
//   max_output_coordinate (1e4)  every output of every phase must be finite, and its positions
//                                and line parameters within this of the origin (bounded)
//   rate (1.0), storm_factor (10.0), max_storm_latency_s (2.0), min_output_fraction (0.5: outputs
//   per trigger in pass B), settle_s (2.0: wall time after each phase)
//   compare: identical  | min_identical_fraction (outputs with the same stamp in A and B that are
//                          byte-identical after the header)
//            image      | min_pixel_agreement (mean share of equal pixels, same-stamp images)
//            pose_truth | truth_topic (PoseStamped in the bag), max_final_position_error_m,
//                          max_final_heading_error_deg (last output of B)
//            box        | min_box_iou_fraction (TrackedObject: share of same-stamp frames whose
//            boxes
//                          in A and B overlap with IoU >= 0.5)
//            place      | min_place_agreement (PlaceRecognition: share of same-stamp results naming
//                          the same place)
//   bad_reconfigure (string list, "name=value": doubles, "nan" and "inf" included), sent one at a
//   time to <node>/set_parameters
//   stall_service (string: the service's full name), stall_service_type (std_srvs/Trigger |
//   std_srvs/Empty | adaptive_perception/SaveMap), stall_answer_timeout_s (10)
#include <dynamic_reconfigure/Reconfigure.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <gtest/gtest.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/LaserScan.h>
#include <std_srvs/Empty.h>
#include <std_srvs/Trigger.h>
#include <topic_tools/shape_shifter.h>
#include <xmlrpcpp/XmlRpc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <future>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "adaptive_perception/LineSegmentArray.h"
#include "adaptive_perception/PlaceRecognition.h"
#include "adaptive_perception/SaveMap.h"
#include "adaptive_perception/TrackedObject.h"
#include "rostest_support.h"

namespace ap = adaptive_perception;
namespace support = adaptive_perception::rostest_support;
using topic_tools::ShapeShifter;

namespace {

struct Recorded {
  ros::Time stamp;
  ros::WallTime received;
  ShapeShifter::ConstPtr msg;
  std::vector<uint8_t> payload;  // bytes after the header
};

/// Records every output with its stamp and arrival time, in the phase it arrived in.
class OutputRecorder {
 public:
  void onMessage(const ShapeShifter::ConstPtr& m) {
    Recorded r;
    r.received = ros::WallTime::now();
    r.msg = m;
    std_msgs::Header h;
    std::size_t header_bytes = 0;
    const std::vector<uint8_t> buf = support::serialized(*m);
    if (!support::leadingHeader(buf, &h, &header_bytes)) return;
    r.stamp = h.stamp;
    r.payload.assign(buf.begin() + static_cast<long>(header_bytes), buf.end());
    std::lock_guard<std::mutex> l(mutex_);
    phases_[phase_].push_back(std::move(r));
  }
  void setPhase(const std::string& p) {
    std::lock_guard<std::mutex> l(mutex_);
    phase_ = p;
  }
  std::vector<Recorded> phase(const std::string& p) {
    std::lock_guard<std::mutex> l(mutex_);
    return phases_[p];
  }

 private:
  std::mutex mutex_;
  std::string phase_ = "startup";
  std::map<std::string, std::vector<Recorded>> phases_;
};

/// A copy of `m` (a message that starts with a Header) stamped `shift_s` seconds later.
ShapeShifter::Ptr withStampShifted(const ShapeShifter& m, double shift_s) {
  std::vector<uint8_t> buf = support::serialized(m);
  std_msgs::Header h;
  std::size_t n = 0;
  if (!support::leadingHeader(buf, &h, &n)) return nullptr;
  h.stamp += ros::Duration(shift_s);  // same length on the wire: written over the old header
  ros::serialization::OStream out(buf.data(), static_cast<uint32_t>(n));
  ros::serialization::serialize(out, h);
  auto s = boost::make_shared<ShapeShifter>();
  s->morph(m.getMD5Sum(), m.getDataType(), m.getMessageDefinition(), "");
  ros::serialization::IStream in(buf.data(), static_cast<uint32_t>(buf.size()));
  s->read(in);
  return s;
}

struct BagMessage {
  std::string topic;
  ros::Time time;
  ShapeShifter::ConstPtr msg;
};

/// Publishes a bag's messages (and /clock) paced on the wall clock, remembering when each trigger
/// stamp was sent.
class Replayer {
 public:
  Replayer(ros::NodeHandle& nh, const std::string& bag_path, const std::vector<std::string>& topics,
           std::string trigger)
      : trigger_(std::move(trigger)) {
    rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
    std::vector<std::string> query = topics;
    for (const std::string& t : topics) query.push_back("/" + t);
    rosbag::View view(bag, rosbag::TopicQuery(query));
    for (const rosbag::MessageInstance& m : view) {
      std::string topic = m.getTopic();
      if (!topic.empty() && topic[0] == '/') topic.erase(0, 1);
      auto s = m.instantiate<ShapeShifter>();
      if (!pubs_.count(topic)) pubs_[topic] = s->advertise(nh, topic, 1000, topic == "tf_static");
      messages_.push_back({topic, m.getTime(), s});
    }
    clock_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  }
  bool empty() const { return messages_.empty(); }
  ros::Time begin() const { return messages_.front().time; }
  ros::Time end() const { return messages_.back().time; }
  const std::vector<BagMessage>& messages() const { return messages_; }
  ros::Publisher& publisher(const std::string& topic) { return pubs_.at(topic); }
  std::size_t triggerSubscribers() const {
    auto it = pubs_.find(trigger_);
    return it == pubs_.end() ? 0 : it->second.getNumSubscribers();
  }
  void publishClock(const ros::Time& t) {
    rosgraph_msgs::Clock c;
    c.clock = t;
    clock_.publish(c);
  }
  /// Plays the whole bag at `rate`; returns the number of trigger messages sent. With jitter_s > 0
  /// every trigger message is sent again right after it, stamped jitter_s seconds earlier (a second
  /// publisher re-sending old messages); those stamps are remembered (jittered()).
  int play(double rate, double jitter_s = 0.0) {
    const ros::WallTime start = ros::WallTime::now();
    int triggers = 0;
    for (const BagMessage& m : messages_) {
      if (!ros::ok()) break;
      const ros::WallTime due = start + ros::WallDuration((m.time - begin()).toSec() / rate);
      const ros::WallDuration wait = due - ros::WallTime::now();
      if (wait > ros::WallDuration(0)) wait.sleep();
      publishClock(m.time);
      if (m.topic == trigger_) {
        std_msgs::Header h;
        std::size_t n = 0;
        if (support::leadingHeader(support::serialized(*m.msg), &h, &n)) {
          std::lock_guard<std::mutex> l(mutex_);
          sent_[h.stamp] = ros::WallTime::now();
        }
        ++triggers;
      }
      pubs_.at(m.topic).publish(*m.msg);
      if (jitter_s > 0.0 && m.topic == trigger_) {
        if (ShapeShifter::Ptr old = withStampShifted(*m.msg, -jitter_s)) {
          std_msgs::Header h;
          std::size_t n = 0;
          support::leadingHeader(support::serialized(*old), &h, &n);
          {
            std::lock_guard<std::mutex> l(mutex_);
            jittered_.insert(h.stamp);
          }
          pubs_.at(m.topic).publish(*old);
        }
      }
    }
    return triggers;
  }
  bool jittered(const ros::Time& stamp) {
    std::lock_guard<std::mutex> l(mutex_);
    return jittered_.count(stamp) > 0;
  }
  /// Wall time at which the trigger with this stamp was last sent (zero when never).
  ros::WallTime sentAt(const ros::Time& stamp) {
    std::lock_guard<std::mutex> l(mutex_);
    auto it = sent_.find(stamp);
    return it == sent_.end() ? ros::WallTime() : it->second;
  }

 private:
  std::string trigger_;
  std::vector<BagMessage> messages_;
  std::map<std::string, ros::Publisher> pubs_;
  ros::Publisher clock_;
  std::mutex mutex_;
  std::map<ros::Time, ros::WallTime> sent_;
  std::set<ros::Time> jittered_;
};

template <typename T>
boost::shared_ptr<T> firstOf(const Replayer& r, const std::string& topic) {
  for (const BagMessage& m : r.messages())
    if (m.topic == topic) return m.msg->instantiate<T>();
  return nullptr;
}

// ---- hostile messages
// ----------------------------------------------------------------------------

/// Named variants of a good message, each a changed copy stamped 10 ms after the one before it
/// (from `stamp`), so that no two are taken for one message.
template <class M>
class Variants {
 public:
  Variants(M good, const ros::Time& stamp) : good_(std::move(good)), stamp_(stamp) {}
  template <class F>
  Variants& add(const std::string& name, F change) {
    M m = good_;
    change(m);
    m.header.stamp = stamp_ + ros::Duration(0.01 * static_cast<double>(list_.size() + 1));
    list_.emplace_back(name, std::move(m));
    return *this;
  }
  /// The good message 1,000 s older than `stamp`: no tf reaches that far back.
  Variants& addStale() {
    list_.emplace_back("stale stamp (1,000 s old, no tf)", good_);
    list_.back().second.header.stamp = stamp_ - ros::Duration(1000.0);
    return *this;
  }
  std::vector<std::pair<std::string, M>> list() const { return list_; }

 private:
  M good_;
  ros::Time stamp_;
  std::vector<std::pair<std::string, M>> list_;
};

/// A change that makes an image one row of `width` pixels in `encoding` with `bytes` of data
/// (and that step): a size whose byte count wraps in 32 bits.
auto oneRow(const std::string& encoding, uint32_t width, uint32_t bytes) {
  return [=](sensor_msgs::Image& m) {
    m.encoding = encoding;
    m.width = width;
    m.height = 1;
    m.step = bytes;
    m.data.assign(bytes, 0);
  };
}

std::vector<std::pair<std::string, sensor_msgs::Image>> hostileImages(
    const sensor_msgs::Image& good, const ros::Time& stamp) {
  using M = sensor_msgs::Image;
  Variants<M> v(good, stamp);
  v.add("unsupported encoding 32FC1", [](M& m) { m.encoding = "32FC1"; })
      .add("unknown encoding", [](M& m) { m.encoding = "no_such_encoding"; })
      .add("zero-size image",
           [](M& m) {
             m.width = m.height = m.step = 0;
             m.data.clear();
           })
      .add("step smaller than a row", [](M& m) { m.step = m.step / 2; })
      .add("data shorter than step x height", [](M& m) { m.data.resize(m.data.size() / 2); })
      .add("dimensions far larger than the data", [](M& m) { m.width = m.height = 100000; })
      .add("step overflowing step x height",
           [](M& m) { m.step = std::numeric_limits<uint32_t>::max(); })
      .add("bgr8 width whose row size wraps in 32 bits (1431655766 x 1, step 2)",
           oneRow("bgr8", 1431655766u, 2))
      .add("yuv422 width 0x80000002 (a negative int)", oneRow("yuv422", 0x80000002u, 4))
      .add("valid image of another size", [](M& m) {
        m.width /= 2;
        m.height /= 2;
        m.step /= 2;
        m.data.assign(static_cast<std::size_t>(m.step) * m.height, 128);
      });
  if (good.encoding == "yuv422") v.add("yuv422 with an odd width", [](M& m) { m.width -= 1; });
  v.add("frame with no tf", [](M& m) { m.header.frame_id = "no_such_frame"; })
      .add("empty frame id", [](M& m) { m.header.frame_id.clear(); })
      .addStale();
  return v.list();
}

std::vector<std::pair<std::string, sensor_msgs::LaserScan>> hostileScans(
    const sensor_msgs::LaserScan& good, const ros::Time& stamp) {
  using M = sensor_msgs::LaserScan;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const auto all = [](float r) {
    return [r](M& m) { std::fill(m.ranges.begin(), m.ranges.end(), r); };
  };
  return Variants<M>(good, stamp)
      .add("all ranges NaN", all(nan))
      .add("all ranges +inf", all(inf))
      .add("all ranges negative", all(-1.0f))
      .add("every third range NaN or -inf",
           [&](M& m) {
             for (std::size_t i = 0; i < m.ranges.size(); i += 3)
               m.ranges[i] = (i % 2) ? nan : -inf;
           })
      .add("zero beams",
           [](M& m) {
             m.ranges.clear();
             m.intensities.clear();
           })
      .add("more ranges than the angles cover",
           [](M& m) { m.ranges.resize(m.ranges.size() * 3, 1.0f); })
      .add("zero angle increment", [](M& m) { m.angle_increment = 0.0f; })
      .add("NaN angle increment", [&](M& m) { m.angle_increment = nan; })
      .add("infinite angle_min", [&](M& m) { m.angle_min = inf; })
      .add("zero range_max", [](M& m) { m.range_max = 0.0f; })
      .add("range_min above range_max", [](M& m) { m.range_min = m.range_max + 1.0f; })
      .add("intensities of another length", [](M& m) { m.intensities.assign(3, 1.0f); })
      .add("frame with no tf", [](M& m) { m.header.frame_id = "no_such_frame"; })
      .list();
}

std::vector<std::pair<std::string, ap::LineSegmentArray>> hostileLines(const std::string& frame,
                                                                       const ros::Time& stamp) {
  using M = ap::LineSegmentArray;
  ap::LineSegment s;
  s.rho = 2.0;
  s.alpha = 0.3;
  s.covariance = {1e-4, 0.0, 0.0, 1e-4};
  s.start.x = 2.0;
  s.start.y = -1.0;
  s.end.x = 1.5;
  s.end.y = 2.0;
  s.num_points = 50;
  M good;
  good.header.frame_id = frame;
  good.segments = {s};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const auto segment = [](std::function<void(ap::LineSegment&)> change) {
    return [change](M& m) { change(m.segments[0]); };
  };
  return Variants<M>(good, stamp)
      .add("no segments", [](M& m) { m.segments.clear(); })
      .add("NaN rho", segment([&](ap::LineSegment& b) { b.rho = nan; }))
      .add("infinite alpha", segment([&](ap::LineSegment& b) { b.alpha = inf; }))
      .add("negative rho", segment([](ap::LineSegment& b) { b.rho = -3.0; }))
      .add("negative variance", segment([](ap::LineSegment& b) {
             b.covariance = {-1e-4, 0.0, 0.0, 1e-4};
           }))
      .add("covariance not positive definite", segment([](ap::LineSegment& b) {
             b.covariance = {1e-4, 1.0, 1.0, 1e-4};
           }))
      .add("zero covariance", segment([](ap::LineSegment& b) {
             b.covariance = {0.0, 0.0, 0.0, 0.0};
           }))
      .add("NaN covariance", segment([&](ap::LineSegment& b) {
             b.covariance = {nan, 0.0, 0.0, nan};
           }))
      .add("infinite endpoint", segment([&](ap::LineSegment& b) { b.start.x = inf; }))
      .add("a thousand identical segments", [&](M& m) { m.segments.assign(1000, s); })
      .add("frame with no tf", [](M& m) { m.header.frame_id = "no_such_frame"; })
      .add("empty frame id", [](M& m) { m.header.frame_id.clear(); })
      .addStale()
      .list();
}

/// Pose inputs a node must refuse: each would kill it, or turn its estimate to NaN, if taken.
std::vector<std::pair<std::string, geometry_msgs::PoseWithCovarianceStamped>> hostilePoses(
    const std::string& frame, const ros::Time& stamp) {
  using M = geometry_msgs::PoseWithCovarianceStamped;
  M good;
  good.header.frame_id = frame;
  good.pose.pose.position.x = 0.5;
  good.pose.pose.position.y = -0.5;
  good.pose.pose.orientation.w = 1.0;
  good.pose.covariance[0] = good.pose.covariance[7] = 0.25;  // rviz's
  good.pose.covariance[35] = 0.068;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  return Variants<M>(good, stamp)
      .add("yaw-x covariance on one side only (covariance[30] = 10)",
           [](M& m) { m.pose.covariance[30] = 10.0; })
      .add("NaN yaw-x covariance (covariance[30])", [&](M& m) { m.pose.covariance[30] = nan; })
      .add("NaN x-y covariance", [&](M& m) { m.pose.covariance[1] = m.pose.covariance[6] = nan; })
      .add("x-y covariance not positive definite",
           [](M& m) { m.pose.covariance[1] = m.pose.covariance[6] = 1.0; })
      .add("infinite x variance", [&](M& m) { m.pose.covariance[0] = inf; })
      .add("NaN position", [&](M& m) { m.pose.pose.position.x = nan; })
      .add("zero quaternion", [](M& m) { m.pose.pose.orientation.w = 0.0; })
      .add("NaN quaternion", [&](M& m) { m.pose.pose.orientation.z = nan; })
      .list();
}

/// Why an output is not finite or not bounded (|coordinate| <= bound), or "": the published
/// types whose numbers mean positions or line parameters are read; others pass.
std::string outputProblem(const Recorded& r, double bound) {
  std::string why;
  const auto check = [&](double v, const char* what) {
    if (why.empty() && !(std::isfinite(v) && std::abs(v) <= bound))
      why = std::string(what) + " = " + std::to_string(v);
  };
  const std::string type = r.msg->getDataType();
  if (type == "geometry_msgs/PoseWithCovarianceStamped") {
    auto m = r.msg->instantiate<geometry_msgs::PoseWithCovarianceStamped>();
    const auto& p = m->pose.pose;
    check(p.position.x, "position.x");
    check(p.position.y, "position.y");
    check(p.position.z, "position.z");
    check(p.orientation.x, "orientation.x");
    check(p.orientation.y, "orientation.y");
    check(p.orientation.z, "orientation.z");
    check(p.orientation.w, "orientation.w");
    for (double c : m->pose.covariance) check(c, "a covariance entry");
  } else if (type == "adaptive_perception/LineSegmentArray") {
    auto m = r.msg->instantiate<ap::LineSegmentArray>();
    for (const auto& l : m->segments) {
      check(l.rho, "rho");
      check(l.alpha, "alpha");
      for (double c : l.covariance) check(c, "a line covariance entry");
      check(l.start.x, "start.x");
      check(l.start.y, "start.y");
      check(l.end.x, "end.x");
      check(l.end.y, "end.y");
    }
  } else if (type == "adaptive_perception/TrackedObject") {
    auto m = r.msg->instantiate<ap::TrackedObject>();
    check(m->box.x_offset, "box.x_offset");
    check(m->box.y_offset, "box.y_offset");
    check(m->box.width, "box.width");
    check(m->box.height, "box.height");
  }
  return why;
}

// ---- dynamic_reconfigure and services
// ------------------------------------------------------------

/// Sends `request` to <node>/set_parameters; the reply is the configuration the node holds after
/// it.
bool reconfigure(const std::string& node, const dynamic_reconfigure::Config& request,
                 dynamic_reconfigure::Config* reply) {
  dynamic_reconfigure::Reconfigure srv;
  srv.request.config = request;
  const std::string name = "/" + node + "/set_parameters";
  if (!ros::service::waitForService(name, ros::Duration(10.0))) return false;
  if (!ros::service::call(name, srv)) return false;
  *reply = srv.response.config;
  return true;
}

/// "name=value" as a one-double reconfigure request.
dynamic_reconfigure::Config doubleSetting(const std::string& setting) {
  dynamic_reconfigure::Config c;
  dynamic_reconfigure::DoubleParameter d;
  const std::size_t eq = setting.find('=');
  d.name = setting.substr(0, eq);
  d.value = std::strtod(setting.substr(eq + 1).c_str(), nullptr);  // "nan", "inf" parse
  c.doubles.push_back(d);
  return c;
}

/// Calls a service of one of the types the nodes offer; false when the call failed.
bool callService(const std::string& name, const std::string& type, std::string* what) {
  if (type == "std_srvs/Trigger") {
    std_srvs::Trigger srv;
    const bool ok = ros::service::call(name, srv);
    *what = srv.response.message;
    return ok;
  }
  if (type == "std_srvs/Empty") {
    std_srvs::Empty srv;
    return ros::service::call(name, srv);
  }
  if (type == "adaptive_perception/SaveMap") {
    ap::SaveMap srv;
    srv.request.path = (std::filesystem::temp_directory_path() /
                        ("hostile_stall_map_" + std::to_string(::getpid()) + ".yaml"))
                           .string();
    srv.request.overwrite = true;
    const bool ok = ros::service::call(name, srv);
    *what = srv.response.message;
    std::filesystem::remove(srv.request.path);
    return ok;
  }
  *what = "unknown stall_service_type " + type;
  return false;
}

double yawOf(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

double iou(const sensor_msgs::RegionOfInterest& a, const sensor_msgs::RegionOfInterest& b) {
  const double x0 = std::max(a.x_offset, b.x_offset), y0 = std::max(a.y_offset, b.y_offset);
  const double x1 = std::min(a.x_offset + a.width, b.x_offset + b.width);
  const double y1 = std::min(a.y_offset + a.height, b.y_offset + b.height);
  const double inter = std::max(0.0, x1 - x0) * std::max(0.0, y1 - y0);
  const double uni =
      static_cast<double>(a.width) * a.height + static_cast<double>(b.width) * b.height - inter;
  return uni > 0.0 ? inter / uni : 0.0;
}

std::map<ros::Time, const Recorded*> byStamp(const std::vector<Recorded>& v) {
  std::map<ros::Time, const Recorded*> m;
  for (const Recorded& r : v) m[r.stamp] = &r;
  return m;
}

TEST(HostileInput, KeepsPublishingCorrectOutput) {
  ros::NodeHandle nh, p("~");
  std::string bag_path = p.param<std::string>("bag", "");
  const std::string bag_command = p.param<std::string>("bag_command", "");
  std::filesystem::path temp_dir;
  if (!bag_command.empty()) {
    temp_dir =
        std::filesystem::temp_directory_path() / ("hostile_input_" + std::to_string(::getpid()));
    std::filesystem::create_directories(temp_dir);
    bag_path = (temp_dir / "input.bag").string();
    const std::string cmd = "BAG='" + bag_path + "' bash -c '" + bag_command + "' > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << "bag_command failed: " << bag_command;
  }
  std::vector<std::string> topics;
  p.getParam("replay_topics", topics);
  const std::string trigger = p.param<std::string>("trigger_topic", "");
  const std::string output = p.param<std::string>("output_topic", "");
  const std::string node = p.param<std::string>("node", "");
  const std::string image_topic = p.param<std::string>("image_topic", "");
  const std::string scan_topic = p.param<std::string>("scan_topic", "");
  const std::string lines_topic = p.param<std::string>("lines_topic", "");
  const std::string pose_topic = p.param<std::string>("pose_topic", "");
  const double rate = p.param("rate", 1.0), storm_factor = p.param("storm_factor", 10.0);
  const double max_storm_latency = p.param("max_storm_latency_s", 2.0);
  const double min_output_fraction = p.param("min_output_fraction", 0.5);
  const double settle = p.param("settle_s", 2.0);
  const std::string compare = p.param<std::string>("compare", "identical");
  ASSERT_FALSE(topics.empty() || trigger.empty() || output.empty() || node.empty())
      << "set replay_topics, trigger_topic, output_topic and node";

  // A launch node may still be making the bag (and the node's database) when the test starts.
  const double startup_timeout = p.param("startup_timeout_s", 60.0);
  ASSERT_TRUE(
      support::waitUntil([&] { return std::filesystem::exists(bag_path); }, startup_timeout, 0.5))
      << bag_path << " did not appear within " << startup_timeout << " s";
  if (p.param("remove_bag_dir", false)) temp_dir = std::filesystem::path(bag_path).parent_path();
  Replayer replay(nh, bag_path, topics, trigger);
  ASSERT_FALSE(replay.empty()) << "no messages of the replay topics in " << bag_path;
  OutputRecorder recorder;
  ros::Subscriber out_sub = nh.subscribe<ShapeShifter>(
      output, 1000, [&](const ShapeShifter::ConstPtr& m) { recorder.onMessage(m); });
  ros::AsyncSpinner spinner(2);
  spinner.start();
  replay.publishClock(replay.begin());
  ASSERT_TRUE(support::waitUntil([&] { return replay.triggerSubscribers() > 0; }, startup_timeout))
      << node << " never subscribed to " << trigger;
  ros::WallDuration(1.0).sleep();  // the node's tf listener and publishers connect

  // Pass A: the reference.
  recorder.setPhase("A");
  const int triggers = replay.play(rate);
  ros::WallDuration(settle).sleep();
  const std::vector<Recorded> a = recorder.phase("A");
  std::printf("hostile_input: %s pass A: %d inputs, %zu outputs\n", node.c_str(), triggers,
              a.size());
  ASSERT_GT(a.size(), 0u) << node << " published nothing on " << output << " for good input";

  // Hostile input, stamped after the bag's end.
  recorder.setPhase("hostile");
  int hostile_cases = 0;
  const ros::Time after = replay.end() + ros::Duration(1.0);
  replay.publishClock(after);
  auto send = [&](ros::Publisher& pub, const auto& cases) {
    for (const auto& [name, msg] : cases) {
      std::printf("hostile_input: %s <- %s\n", node.c_str(), name.c_str());
      for (int k = 0; k < 3; ++k) {
        pub.publish(msg);
        ros::WallDuration(0.05).sleep();
      }
      ++hostile_cases;
    }
  };
  if (!image_topic.empty()) {
    auto good = firstOf<sensor_msgs::Image>(replay, image_topic);
    ASSERT_TRUE(good) << "no " << image_topic << " in the bag";
    send(replay.publisher(image_topic), hostileImages(*good, after));
  }
  if (!scan_topic.empty()) {
    auto good = firstOf<sensor_msgs::LaserScan>(replay, scan_topic);
    ASSERT_TRUE(good) << "no " << scan_topic << " in the bag";
    send(replay.publisher(scan_topic), hostileScans(*good, after));
  }
  ros::Publisher lines_pub;
  if (!lines_topic.empty()) {
    lines_pub = nh.advertise<ap::LineSegmentArray>(lines_topic, 100);
    support::waitUntil([&] { return lines_pub.getNumSubscribers() > 0; }, 10.0);
    send(lines_pub, hostileLines(p.param<std::string>("lines_frame", "laser"), after));
  }
  ros::Publisher pose_pub;
  if (!pose_topic.empty()) {
    pose_pub = nh.advertise<geometry_msgs::PoseWithCovarianceStamped>(pose_topic, 100);
    ASSERT_TRUE(support::waitUntil([&] { return pose_pub.getNumSubscribers() > 0; }, 10.0))
        << node << " does not subscribe to " << pose_topic;
    send(pose_pub, hostilePoses(p.param<std::string>("pose_frame", "map"), after));
  }
  ros::WallDuration(settle).sleep();

  // Bad settings through dynamic_reconfigure (NaN passes its min/max clamp).
  std::vector<std::string> bad_settings;
  p.getParam("bad_reconfigure", bad_settings);
  dynamic_reconfigure::Config original;
  if (!bad_settings.empty()) {
    ASSERT_TRUE(reconfigure(node, dynamic_reconfigure::Config(), &original))
        << node << "/set_parameters does not answer";
    for (const std::string& setting : bad_settings) {
      dynamic_reconfigure::Config reply;
      std::printf("hostile_input: %s reconfigure %s\n", node.c_str(), setting.c_str());
      ASSERT_TRUE(reconfigure(node, doubleSetting(setting), &reply))
          << node << " did not answer reconfigure " << setting;
      for (const auto& d : reply.doubles)
        EXPECT_TRUE(std::isfinite(d.value))
            << node << " took " << d.name << " = " << d.value << " from " << setting;
      ros::WallDuration(0.5).sleep();
    }
  }

  // The storm: the bag at storm_factor x the rate; time jumps backwards at its start.
  recorder.setPhase("storm");
  const int storm_triggers = replay.play(rate * storm_factor);
  ros::WallDuration(settle).sleep();
  const std::vector<Recorded> storm = recorder.phase("storm");
  double max_latency = 0.0;
  int timed = 0;
  for (const Recorded& r : storm) {
    const ros::WallTime sent = replay.sentAt(r.stamp);
    if (sent.isZero()) continue;
    max_latency = std::max(max_latency, (r.received - sent).toSec());
    ++timed;
  }
  std::printf("hostile_input: %s storm: %d inputs at %.0fx, %zu outputs, max latency %.3f s\n",
              node.c_str(), storm_triggers, storm_factor, storm.size(), max_latency);
  EXPECT_GT(timed, 0) << node << " published nothing during the storm";
  EXPECT_LE(max_latency, max_storm_latency) << node << " fell behind the storm";

  if (!bad_settings.empty()) {
    dynamic_reconfigure::Config reply;
    ASSERT_TRUE(reconfigure(node, original, &reply)) << node << " died after the bad settings";
  }

  // Pass B: good input again, from the start; with jitter_s, every input is re-sent that much
  // older.
  const double jitter = p.param("jitter_s", 0.0);
  recorder.setPhase("B");
  replay.play(rate, jitter);
  ros::WallDuration(settle).sleep();
  recorder.setPhase("end");
  const std::vector<Recorded> b = recorder.phase("B");
  if (jitter > 0.0) {
    // A node may take an older copy when its queue dropped the newer original before it saw it;
    // it must never take one after a newer input: its outputs' stamps never go back.
    long older_copies = 0, went_back = 0;
    ros::Time newest;
    for (const Recorded& r : b) {
      older_copies += replay.jittered(r.stamp);
      if (r.stamp < newest) ++went_back;
      newest = std::max(newest, r.stamp);
    }
    std::printf(
        "hostile_input: %s pass B with every input re-sent %.3f s older: %zu outputs, "
        "%ld for older copies, %ld stamped before an earlier output\n",
        node.c_str(), jitter, b.size(), older_copies, went_back);
    EXPECT_EQ(went_back, 0) << node << " took inputs older than one it had taken";
  }
  std::printf("hostile_input: %s survived %d hostile cases; pass B: %zu outputs for %d inputs\n",
              node.c_str(), hostile_cases, b.size(), triggers);
  EXPECT_GE(static_cast<double>(b.size()), min_output_fraction * triggers)
      << node << " stopped publishing after the hostile input";

  // Whatever came in, every output was finite and bounded.
  const double bound = p.param("max_output_coordinate", 1e4);
  int outputs_checked = 0;
  for (const char* phase : {"A", "hostile", "storm", "B"}) {
    for (const Recorded& r : recorder.phase(phase)) {
      const std::string why = outputProblem(r, bound);
      EXPECT_EQ(why, "") << node << " published " << why << " in phase " << phase << " at "
                         << r.stamp.toSec() << " s";
      ++outputs_checked;
    }
  }
  std::printf("hostile_input: %s %d outputs checked for finite values within %g\n", node.c_str(),
              outputs_checked, bound);

  const auto ma = byStamp(a), mb = byStamp(b);
  if (compare == "identical" || compare == "image" || compare == "box" || compare == "place") {
    int both = 0, agree = 0;
    double pixel_agreement = 0.0;
    for (const auto& [stamp, rb] : mb) {
      auto it = ma.find(stamp);
      if (it == ma.end()) continue;
      const Recorded& ra = *it->second;
      ++both;
      if (compare == "identical") {
        agree += ra.payload == rb->payload;
      } else if (compare == "image") {
        auto ia = ra.msg->instantiate<sensor_msgs::Image>();
        auto ib = rb->msg->instantiate<sensor_msgs::Image>();
        if (ia->data.size() != ib->data.size() || ia->data.empty()) continue;
        std::size_t same = 0;
        for (std::size_t i = 0; i < ia->data.size(); ++i) same += ia->data[i] == ib->data[i];
        pixel_agreement += static_cast<double>(same) / static_cast<double>(ia->data.size());
      } else if (compare == "box") {
        auto oa = ra.msg->instantiate<ap::TrackedObject>();
        auto ob = rb->msg->instantiate<ap::TrackedObject>();
        agree += !oa->lost && !ob->lost && iou(oa->box, ob->box) >= 0.5;
      } else {
        const std::string pa = ra.msg->instantiate<ap::PlaceRecognition>()->place;
        const std::string pb = rb->msg->instantiate<ap::PlaceRecognition>()->place;
        if (pa == pb) {
          ++agree;
        } else if (both - agree <= 3) {  // the first disagreements, to see where they start
          std::printf("hostile_input: %s at %.3f s: pass A '%s', pass B '%s'\n", node.c_str(),
                      (stamp - replay.begin()).toSec(), pa.c_str(), pb.c_str());
        }
      }
    }
    ASSERT_GT(both, 0) << "no stamp has an output in both passes";
    if (compare == "image") {
      const double mean = pixel_agreement / both;
      std::printf("hostile_input: %s A vs B: %d frames, mean pixel agreement %.4f\n", node.c_str(),
                  both, mean);
      EXPECT_GE(mean, p.param("min_pixel_agreement", 0.95));
    } else {
      const double frac = static_cast<double>(agree) / both;
      std::printf("hostile_input: %s A vs B (%s): %d of %d outputs agree (%.3f)\n", node.c_str(),
                  compare.c_str(), agree, both, frac);
      const std::string key = compare == "identical" ? "min_identical_fraction"
                              : compare == "box"     ? "min_box_iou_fraction"
                                                     : "min_place_agreement";
      EXPECT_GE(frac, p.param(key, 0.9));
    }
  } else if (compare == "pose_truth") {
    const std::string truth_topic = p.param<std::string>("truth_topic", "ground_truth/pose");
    std::map<ros::Time, geometry_msgs::Pose> truth;
    {
      rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
      for (const rosbag::MessageInstance& m :
           rosbag::View(bag, rosbag::TopicQuery({truth_topic, "/" + truth_topic})))
        if (auto t = m.instantiate<geometry_msgs::PoseStamped>()) truth[t->header.stamp] = t->pose;
    }
    ASSERT_FALSE(truth.empty()) << "no " << truth_topic << " in the bag";
    auto finalError = [&](const std::vector<Recorded>& pass, double* pos_m, double* yaw_deg) {
      if (pass.empty()) return false;
      auto est = pass.back().msg->instantiate<geometry_msgs::PoseWithCovarianceStamped>();
      auto t = truth.lower_bound(est->header.stamp);
      if (t == truth.end()) t = std::prev(t);
      const auto& e = est->pose.pose;
      *pos_m = std::hypot(e.position.x - t->second.position.x, e.position.y - t->second.position.y);
      double d = yawOf(e.orientation) - yawOf(t->second.orientation);
      *yaw_deg = std::abs(std::remainder(d, 2.0 * M_PI)) * 180.0 / M_PI;
      return true;
    };
    double pa = 0, ya = 0, pb = 0, yb = 0;
    ASSERT_TRUE(finalError(a, &pa, &ya));
    ASSERT_TRUE(finalError(b, &pb, &yb));
    std::printf("hostile_input: %s final error: pass A %.3f m %.2f deg, pass B %.3f m %.2f deg\n",
                node.c_str(), pa, ya, pb, yb);
    EXPECT_LE(pb, p.param("max_final_position_error_m", 0.2));
    EXPECT_LE(yb, p.param("max_final_heading_error_deg", 10.0));
  } else {
    FAIL() << "unknown compare '" << compare << "'";
  }

  // The clock stops while an input waits for a transform that never comes: services still answer.
  const std::string stall_service = p.param<std::string>("stall_service", "");
  if (!stall_service.empty()) {
    const std::string type = p.param<std::string>("stall_service_type", "std_srvs/Trigger");
    const double answer_timeout = p.param("stall_answer_timeout_s", 10.0);
    ASSERT_TRUE(ros::service::waitForService(stall_service, ros::Duration(10.0)))
        << stall_service << " is not advertised";
    const ros::Time stopped = replay.end() + ros::Duration(5.0);
    replay.publishClock(stopped);
    ros::WallDuration(0.5).sleep();
    const std::string kNoTfFrame = "hostile_stall_no_tf";
    if (!lines_topic.empty()) {
      ap::LineSegmentArray lines;
      lines.header.stamp = stopped;
      lines.header.frame_id = kNoTfFrame;
      lines_pub.publish(lines);
    } else {
      ASSERT_FALSE(image_topic.empty()) << "stall_service needs image_topic or lines_topic";
      sensor_msgs::Image image = *firstOf<sensor_msgs::Image>(replay, image_topic);
      image.header.stamp = stopped;
      image.header.frame_id = kNoTfFrame;
      replay.publisher(image_topic).publish(image);
    }
    ros::WallDuration(1.0).sleep();  // the input now waits for tf, and the clock stands still
    auto answer = std::make_shared<std::promise<std::pair<bool, std::string>>>();
    std::future<std::pair<bool, std::string>> answered = answer->get_future();
    std::thread([answer, stall_service, type] {
      std::string what;
      const bool ok = callService(stall_service, type, &what);
      answer->set_value({ok, what});
    }).detach();  // a node that never answers leaves the thread blocked; the test fails below
    const bool in_time = answered.wait_for(std::chrono::duration<double>(answer_timeout)) ==
                         std::future_status::ready;
    std::printf("hostile_input: %s stalled clock: %s %s\n", node.c_str(), stall_service.c_str(),
                in_time ? "answered" : "did not answer");
    ASSERT_TRUE(in_time) << stall_service << " did not answer within " << answer_timeout
                         << " s of wall time while the clock stood still";
    EXPECT_TRUE(answered.get().first) << stall_service << " call failed";
  }

  // Still alive: the master knows it and its process answers (a dead node stays registered).
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  ASSERT_TRUE(ros::master::execute("lookupNode", args, result, payload, false))
      << node << " is not registered";
  std::string host;
  uint32_t port = 0;
  ASSERT_TRUE(ros::network::splitURI(static_cast<std::string>(payload), host, port));
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue pid_args, pid;
  pid_args[0] = ros::this_node::getName();
  EXPECT_TRUE(client.execute("getPid", pid_args, pid)) << node << " does not answer: it died";
  if (!temp_dir.empty()) std::filesystem::remove_all(temp_dir);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "hostile_input");
  return RUN_ALL_TESTS();
}
