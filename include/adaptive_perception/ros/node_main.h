#pragma once
// The shared main() of every node (src/nodes/<node>.cpp, a few lines each):
//
//   namespace adaptive_perception { class ColorEstimatorNode; }
//   int main(int argc, char** argv) {
//     return adaptive_perception::runNode<adaptive_perception::ColorEstimatorNode>(
//         argc, argv, "color_estimator");
//   }
//
// Only declared here, so that a main parses no ROS header: runNode is defined in ros/node_run.h
// (init, the Node class built from the public and private node handles, spin; a construction error
// is reported with ROS_FATAL and exit status 1) and instantiated once per node class at the end of
// its source file in the ROS library (`template int runNode<ColorEstimatorNode>(...);`).
namespace adaptive_perception {

/// Runs `Node` as this process's ROS node `name` until shutdown; returns the exit status.
template <typename Node>
int runNode(int argc, char** argv, const char* name);

}  // namespace adaptive_perception
