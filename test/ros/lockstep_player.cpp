// lockstep_player: plays a bag with /clock like `rosbag play --clock`, but after each message on
// the trigger topic waits until the node under test has answered it: a message on the output
// topic stamped at or after the trigger's stamp (or ~timeout_s of wall time). The rostests of a
// node that drops frames it cannot keep up with (rbpf_localizer) then check the algorithm, not
// the speed of the machine they share with other tests. Speed is measured by the bench_* tools.
//
//   rosrun adaptive_perception lockstep_player BAG _trigger_topic:=camera/image_raw
//       _output_topic:=rbpf_localizer/pose [_timeout_s:=10] [_delay_s:=3] [_lookahead_s:=0.1]
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

#include <atomic>
#include <cstdio>
#include <map>
#include <mutex>

#include "rostest_support.h"

namespace rs = adaptive_perception::rostest_support;

int main(int argc, char** argv) {
  ros::init(argc, argv, "lockstep_player", ros::init_options::AnonymousName);
  if (argc < 2) {
    std::fprintf(stderr, "usage: lockstep_player BAG _trigger_topic:=T _output_topic:=O\n");
    return 2;
  }
  ros::NodeHandle nh, pnh("~");
  const std::string trigger = pnh.param<std::string>("trigger_topic", "");
  const std::string output = pnh.param<std::string>("output_topic", "");
  const double timeout_s = pnh.param("timeout_s", 10.0);
  const double delay_s = pnh.param("delay_s", 3.0);
  const double lookahead_s = pnh.param("lookahead_s", 0.1);
  if (trigger.empty() || output.empty()) {
    std::fprintf(stderr, "lockstep_player: set ~trigger_topic and ~output_topic\n");
    return 2;
  }
  std::mutex mutex;
  ros::Time answered_up_to;
  ros::Subscriber out_sub = nh.subscribe<topic_tools::ShapeShifter>(
      output, 10, [&](const topic_tools::ShapeShifter::ConstPtr& m) {
        std_msgs::Header h;
        std::size_t bytes = 0;
        if (!rs::leadingHeader(rs::serialized(*m), &h, &bytes)) return;
        std::lock_guard<std::mutex> l(mutex);
        if (h.stamp > answered_up_to) answered_up_to = h.stamp;
      });
  ros::AsyncSpinner spinner(1);
  spinner.start();

  rosbag::Bag bag(argv[1], rosbag::bagmode::Read);
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
    const bool ok = rs::waitUntil(
        [&] {
          std::lock_guard<std::mutex> l(mutex);
          return answered_up_to >= pending_stamp;
        },
        timeout_s, 0.002);
    ok ? ++answered : ++timeouts;
    pending = false;
  };
  for (const rosbag::MessageInstance& m : view) {
    if (!ros::ok()) break;
    if (pending && m.getTime() > pending_bag_time + ros::Duration(lookahead_s)) awaitAnswer();
    rosgraph_msgs::Clock clock;
    clock.clock = m.getTime();
    clock_pub.publish(clock);
    const auto msg = m.instantiate<topic_tools::ShapeShifter>();
    pubs[m.getTopic()].publish(*msg);
    const std::string topic = m.getTopic();
    if (topic != trigger && topic != "/" + trigger) continue;
    std_msgs::Header h;
    std::size_t bytes = 0;
    if (!rs::leadingHeader(rs::serialized(*msg), &h, &bytes)) continue;
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
