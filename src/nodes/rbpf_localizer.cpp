// rbpf_localizer: see include/adaptive_perception/ros/rbpf_localizer_node.h.
#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {
class RbpfLocalizerNode;
}

int main(int argc, char** argv) {
  return adaptive_perception::runNode<adaptive_perception::RbpfLocalizerNode>(
      argc, argv, "rbpf_localizer");
}
