// appearance_localizer: see include/adaptive_perception/ros/appearance_localizer_node.h.
#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {
class AppearanceLocalizerNode;
}

int main(int argc, char** argv) {
  return adaptive_perception::runNode<adaptive_perception::AppearanceLocalizerNode>(
      argc, argv, "appearance_localizer");
}
