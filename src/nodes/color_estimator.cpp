// color_estimator: see include/adaptive_perception/ros/color_estimator_node.h.
#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {
class ColorEstimatorNode;
}

int main(int argc, char** argv) {
  return adaptive_perception::runNode<adaptive_perception::ColorEstimatorNode>(
      argc, argv, "color_estimator");
}
