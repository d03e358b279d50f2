// line_extractor: see include/adaptive_perception/ros/line_extractor_node.h.
#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {
class LineExtractorNode;
}

int main(int argc, char** argv) {
  return adaptive_perception::runNode<adaptive_perception::LineExtractorNode>(argc, argv, "line_extractor");
}
