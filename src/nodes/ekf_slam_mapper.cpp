// ekf_slam_mapper: see include/adaptive_perception/ros/ekf_slam_mapper_node.h.
#include "adaptive_perception/ros/node_main.h"

namespace adaptive_perception {
class EkfSlamMapperNode;
}

int main(int argc, char** argv) {
  return adaptive_perception::runNode<adaptive_perception::EkfSlamMapperNode>(argc, argv,
                                                                             "ekf_slam_mapper");
}
