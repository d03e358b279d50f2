// camera_preview: see include/adaptive_perception/ros/camera_preview_node.h.
#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {
class CameraPreviewNode;
}

int main(int argc, char** argv) {
  return adaptive_perception::runNode<adaptive_perception::CameraPreviewNode>(argc, argv,
                                                                              "camera_preview");
}
