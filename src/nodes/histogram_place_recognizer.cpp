// histogram_place_recognizer: see
// include/adaptive_perception/ros/histogram_place_recognizer_node.h.
#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {
class HistogramPlaceRecognizerNode;
}

int main(int argc, char** argv) {
  return adaptive_perception::runNode<adaptive_perception::HistogramPlaceRecognizerNode>(
      argc, argv, "histogram_place_recognizer");
}
