// head_tf_publisher: see include/adaptive_perception/ros/head_tf_publisher_node.h.
#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {
class HeadTfNode;
}

int main(int argc, char** argv) {
  return adaptive_perception::runNode<adaptive_perception::HeadTfNode>(argc, argv,
                                                                       "head_tf_publisher");
}
