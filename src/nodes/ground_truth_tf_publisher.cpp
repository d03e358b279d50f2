// ground_truth_tf_publisher: see include/adaptive_perception/ros/ground_truth_tf_publisher_node.h.
#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {
class GroundTruthTfNode;
}

int main(int argc, char** argv) {
  return adaptive_perception::runNode<adaptive_perception::GroundTruthTfNode>(
      argc, argv, "ground_truth_tf_publisher");
}
