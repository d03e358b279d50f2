#pragma once
// The std_msgs/Header that starts most ROS messages, read from a message of any type (a
// topic_tools::ShapeShifter, as a bag player or a generic subscriber holds it) without knowing the
// type. Used by lockstep_player and the rostests.
#include <ros/serialization.h>
#include <std_msgs/Header.h>
#include <topic_tools/shape_shifter.h>

#include <cstdint>
#include <vector>

namespace adaptive_perception::ros_messages {

/// The bytes of a message as it travels on the wire.
inline std::vector<std::uint8_t> serialized(const topic_tools::ShapeShifter& m) {
  std::vector<std::uint8_t> buf(m.size());
  ros::serialization::OStream out(buf.data(), static_cast<std::uint32_t>(buf.size()));
  m.write(out);
  return buf;
}

/// The header at the start of serialised message bytes and its length in bytes; false when they
/// are too short to hold one. Valid for every message type whose first field is a Header.
inline bool leadingHeader(const std::vector<std::uint8_t>& buf, std_msgs::Header* header,
                          std::size_t* header_bytes) {
  try {
    // IStream only reads, but takes a non-const pointer.
    ros::serialization::IStream in(const_cast<std::uint8_t*>(buf.data()),
                                   static_cast<std::uint32_t>(buf.size()));
    ros::serialization::deserialize(in, *header);
  } catch (const ros::serialization::StreamOverrunException&) {
    return false;
  }
  *header_bytes = ros::serialization::serializationLength(*header);
  return true;
}

}  // namespace adaptive_perception::ros_messages
