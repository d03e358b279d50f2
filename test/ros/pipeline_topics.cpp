// rostest: a pipeline of nodes answers a bag, and the master shows which process publishes and
// which subscribes each topic (field_nodelets.test: three nodelets in one manager;
// compressed_camera.test: nodes on the compressed transport). Parameters:
//   ~min_messages {topic: n}: at least n messages of any type arrive on the topic;
//   ~publishers {topic: node}: the node is the one process publishing the topic;
//   ~subscribers {node: topic}: the node is among the topic's subscribers;
//   ~not_subscribers {node: topic}: the node does not subscribe the topic;
//   ~timeout_s: wall-clock seconds to wait for the messages (default 100).
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <topic_tools/shape_shifter.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <atomic>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "rostest_support.h"

using adaptive_perception::rostest_support::waitUntil;

namespace {

// The parameter server keeps a key with slashes (a topic) as nested namespaces: flatten them back.
void flatten(XmlRpc::XmlRpcValue& v, const std::string& prefix,
             std::map<std::string, std::string>* out) {
  for (auto& [key, value] : v) {
    const std::string name = prefix.empty() ? key : prefix + "/" + key;
    if (value.getType() == XmlRpc::XmlRpcValue::TypeStruct)
      flatten(value, name, out);
    else if (value.getType() == XmlRpc::XmlRpcValue::TypeInt)
      (*out)[name] = std::to_string(static_cast<int>(value));
    else if (value.getType() == XmlRpc::XmlRpcValue::TypeString)
      (*out)[name] = static_cast<std::string>(value);
    else
      ADD_FAILURE() << "parameter " << name << " is neither an integer nor a string";
  }
}

std::map<std::string, std::string> stringMap(const std::string& param) {
  XmlRpc::XmlRpcValue v;
  std::map<std::string, std::string> out;
  if (ros::NodeHandle("~").getParam(param, v) && v.getType() == XmlRpc::XmlRpcValue::TypeStruct)
    flatten(v, "", &out);
  return out;
}

// The master's system state: [publishers, subscribers, services], each [[topic, [nodes]], ...].
std::set<std::string> nodesOn(const std::string& topic, int which) {
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  std::set<std::string> out;
  if (!ros::master::execute("getSystemState", request, response, payload, true)) return out;
  XmlRpc::XmlRpcValue& list = payload[which];
  for (int i = 0; i < list.size(); ++i) {
    if (static_cast<std::string>(list[i][0]) != topic) continue;
    for (int k = 0; k < list[i][1].size(); ++k) out.insert(static_cast<std::string>(list[i][1][k]));
  }
  return out;
}

std::string absolute(const std::string& name) {
  return name.empty() || name[0] == '/' ? name : "/" + name;
}

}  // namespace

TEST(PipelineTopics, TheNodesAnswerAndTheMasterShowsWhoDoesWhat) {
  ros::NodeHandle nh;
  const double timeout_s = ros::NodeHandle("~").param("timeout_s", 100.0);
  const std::map<std::string, std::string> min_messages = stringMap("min_messages");
  ASSERT_FALSE(min_messages.empty()) << "~min_messages names no topic";
  std::map<std::string, std::unique_ptr<std::atomic<int>>> counts;
  std::vector<ros::Subscriber> subs;
  for (const auto& [topic, n] : min_messages) {
    std::atomic<int>* count = (counts[topic] = std::make_unique<std::atomic<int>>(0)).get();
    subs.push_back(nh.subscribe<topic_tools::ShapeShifter>(
        topic, 50, [count](const topic_tools::ShapeShifter::ConstPtr&) { ++*count; }));
  }
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const auto enough = [&] {
    for (const auto& [topic, n] : min_messages)
      if (*counts[topic] < std::stoi(n)) return false;
    return true;
  };
  waitUntil(enough, timeout_s);
  for (const auto& [topic, n] : min_messages) {
    std::printf("pipeline_topics: %s %d messages\n", topic.c_str(), counts[topic]->load());
    EXPECT_GE(counts[topic]->load(), std::stoi(n)) << "messages on " << topic;
  }
  for (const auto& [topic, node] : stringMap("publishers"))
    EXPECT_EQ(nodesOn(absolute(topic), 0), std::set<std::string>{absolute(node)})
        << "the publishers of " << topic;
  for (const auto& [node, topic] : stringMap("subscribers"))
    EXPECT_TRUE(nodesOn(absolute(topic), 1).count(absolute(node)))
        << absolute(node) << " does not subscribe " << topic;
  for (const auto& [node, topic] : stringMap("not_subscribers"))
    EXPECT_FALSE(nodesOn(absolute(topic), 1).count(absolute(node)))
        << absolute(node) << " subscribes " << topic;
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "pipeline_topics");
  ros::NodeHandle lifetime;
  return RUN_ALL_TESTS();
}
