// field_map_publisher: see include/adaptive_perception/ros/field_map_publisher_node.h.
#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {
class FieldMapPublisherNode;
}

int main(int argc, char** argv) {
  return adaptive_perception::runNode<adaptive_perception::FieldMapPublisherNode>(
      argc, argv, "field_map_publisher");
}
