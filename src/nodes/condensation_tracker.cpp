// condensation_tracker: see include/adaptive_perception/ros/condensation_tracker_node.h.
#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {
class CondensationTrackerNode;
}

int main(int argc, char** argv) {
  return adaptive_perception::runNode<adaptive_perception::CondensationTrackerNode>(
      argc, argv, "condensation_tracker");
}
