// lockstep_player: plays a bag with /clock like `rosbag play --clock`, but after each message on
// the trigger topic waits until the node it feeds has answered it: a message on the output topic
// stamped at or after the trigger's stamp (or ~timeout_s of wall time). A node that drops the
// frames it cannot keep up with (rbpf_localizer) then gives the same result on any machine: the
// rostests check the algorithm, not the speed of the machine they share with other tests, and the
// demo's figures are the filter's (field_demo.launch lockstep:=true). Speed is measured by the
// bench_* tools.
//
//   rosrun adaptive_perception lockstep_player BAG _trigger_topic:=camera/image_raw
//       _output_topic:=rbpf_localizer/pose [_rate:=0] [_timeout_s:=10] [_delay_s:=3]
//       [_lookahead_s:=0.1]
// ~rate: 0 plays as fast as the answers come (the rostests); R > 0 at most R times the bag's own
// rate, so on a machine fast enough a demo looks as the robot saw it, and slower only where the
// node needs the time.
// Messages up to lookahead_s of bag time after a trigger are played before the wait (the tf the
// node interpolates at the trigger's stamp arrives after it); keep it below the trigger's period.
//
// Every topic of the bag is republished under its name (relative names resolve in the player's
// namespace). Ends with `lockstep_player: triggers=.. answered=.. timeouts=..` on stdout.
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Clock.h>
#include <topic_tools/shape_shifter.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>

#include "adaptive_perception/ros/message_header.h"

namespace rm = adaptive_perception::ros_messages;

int main(int argc, char** argv) {
  const char* usage =
      "usage: lockstep_player BAG _trigger_topic:=T _output_topic:=O [_rate:=R] [_timeout_s:=S] "
      "[_delay_s:=S] [_lookahead_s:=S]\n";
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h" ||
      std::string(argv[1]).find(":=") != std::string::npos) {
    std::fprintf(stderr, "%s", usage);
    return 2;
  }
  // The bag first: a bad one is reported before the node waits for a master (ros::init sets the
  // _param:= arguments there).
  rosbag::Bag bag;
  try {
    bag.open(argv[1], rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    std::fprintf(stderr, "lockstep_player: %s: %s\n%s", argv[1], e.what(), usage);
    return 2;
  }
  ros::init(argc, argv, "lockstep_player", ros::init_options::AnonymousName);
  ros::NodeHandle nh, pnh("~");
  const std::string trigger = pnh.param<std::string>("trigger_topic", "");
  const std::string output = pnh.param<std::string>("output_topic", "");
  const double timeout_s = pnh.param("timeout_s", 10.0);
  const double delay_s = pnh.param("delay_s", 3.0);
  const double lookahead_s = pnh.param("lookahead_s", 0.1);
  const double rate = pnh.param("rate", 0.0);
  if (trigger.empty() || output.empty()) {
    std::fprintf(stderr, "lockstep_player: set ~trigger_topic and ~output_topic\n");
    return 2;
  }
  if (!(rate >= 0.0) || !(timeout_s > 0.0) || !(delay_s >= 0.0) || !(lookahead_s >= 0.0)) {
    std::fprintf(stderr,
                 "lockstep_player: ~rate, ~delay_s and ~lookahead_s must be >= 0 and ~timeout_s "
                 "> 0 (got %g, %g, %g, %g)\n",
                 rate, delay_s, lookahead_s, timeout_s);
    return 2;
  }
  std::mutex mutex;
  std::condition_variable answer;
  ros::Time answered_up_to;
  ros::Subscriber out_sub = nh.subscribe<topic_tools::ShapeShifter>(
      output, 10, [&](const topic_tools::ShapeShifter::ConstPtr& m) {
        std_msgs::Header h;
        std::size_t bytes = 0;
        if (!rm::leadingHeader(rm::serialized(*m), &h, &bytes)) return;
        {
          std::lock_guard<std::mutex> l(mutex);
          if (h.stamp > answered_up_to) answered_up_to = h.stamp;
        }
        answer.notify_all();
      });
  ros::AsyncSpinner spinner(1);
  spinner.start();

  rosbag::View view(bag);
  ros::Publisher clock_pub = nh.advertise<rosgraph_msgs::Clock>("/clock", 1);
  std::map<std::string, ros::Publisher> pubs;
  for (const rosbag::ConnectionInfo* c : view.getConnections()) {
    if (pubs.count(c->topic)) continue;
    topic_tools::ShapeShifter shape;
    shape.morph(c->md5sum, c->datatype, c->msg_def, "");
    const bool latch = c->topic == "/tf_static" || c->topic == "tf_static";
    pubs[c->topic] = shape.advertise(nh, c->topic, 100, latch);
  }
  ros::WallDuration(delay_s).sleep();  // subscribers connect
  long triggers = 0, answered = 0, timeouts = 0;
  // The trigger waiting for its answer. Messages up to ~lookahead_s of bag time after it go out
  // first: the tf the node interpolates at the trigger's stamp, its camera_info.
  bool pending = false;
  ros::Time pending_stamp, pending_bag_time;
  auto awaitAnswer = [&] {
    const auto deadline =
        std::chrono::steady_clock::now() +
        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
            std::chrono::duration<double>(timeout_s));
    std::unique_lock<std::mutex> l(mutex);
    // Wakes on an answer; looks at ros::ok() every 100 ms.
    while (answered_up_to < pending_stamp && ros::ok() &&
           std::chrono::steady_clock::now() < deadline)
      answer.wait_until(l, std::min(deadline, std::chrono::steady_clock::now() +
                                                  std::chrono::milliseconds(100)));
    const bool ok = answered_up_to >= pending_stamp;
    ok ? ++answered : ++timeouts;
    pending = false;
  };
  // Pacing (rate > 0): each message at most rate times its bag-time gap after the one before.
  ros::WallTime last_wall = ros::WallTime::now();
  ros::Time last_bag;
  for (const rosbag::MessageInstance& m : view) {
    if (!ros::ok()) break;
    if (pending && m.getTime() > pending_bag_time + ros::Duration(lookahead_s)) awaitAnswer();
    if (rate > 0.0) {
      if (!last_bag.isZero() && m.getTime() > last_bag) {
        const ros::WallTime due =
            last_wall + ros::WallDuration((m.getTime() - last_bag).toSec() / rate);
        if (due > ros::WallTime::now()) (due - ros::WallTime::now()).sleep();
      }
      last_wall = ros::WallTime::now();
      last_bag = m.getTime();
    }
    rosgraph_msgs::Clock clock;
    clock.clock = m.getTime();
    clock_pub.publish(clock);
    const auto msg = m.instantiate<topic_tools::ShapeShifter>();
    pubs[m.getTopic()].publish(*msg);
    const std::string topic = m.getTopic();
    if (topic != trigger && topic != "/" + trigger) continue;
    std_msgs::Header h;
    std::size_t bytes = 0;
    if (!rm::leadingHeader(rm::serialized(*msg), &h, &bytes)) continue;
    if (pending) awaitAnswer();
    ++triggers;
    pending = true;
    pending_stamp = h.stamp;
    pending_bag_time = m.getTime();
  }
  if (pending) awaitAnswer();
  ros::WallDuration(1.0).sleep();  // the last outputs arrive
  std::printf("lockstep_player: triggers=%ld answered=%ld timeouts=%ld\n", triggers, answered,
              timeouts);
  return 0;
}
