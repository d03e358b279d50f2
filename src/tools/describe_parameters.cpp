// describe_parameters: prints a node's parameter table (every private parameter it reads, with its
// default, allowed range and what it does), as its doc page shows it; --update rewrites the table
// in docs/nodes/<node>.md (between its markers) from the code.
//
//   describe_parameters --node rbpf_localizer [--update] [--docs DIR (default docs/nodes)]
//   describe_parameters --list
#include <fstream>
#include <iostream>
#include <sstream>

#include "adaptive_perception/io/atomic_file.h"
#include "adaptive_perception/ros/parameter_docs.h"
#include "tool_args.h"

using namespace adaptive_perception;

int main(int argc, char** argv) {
  tools::Args args(argc, argv, "describe_parameters --node NAME [--update] [--docs DIR] | --list");
  const bool list = args.has("list");
  const std::string node = args.get("node", "");
  const bool update = args.has("update");
  const std::string docs = args.get("docs", "docs/nodes");
  args.finish();
  const auto& nodes = ros_params::nodeParameters();
  if (list) {
    for (const auto& [name, rows] : nodes) std::cout << name << " (" << rows.size() << ")\n";
    return 0;
  }
  if (!nodes.count(node)) args.fail("--node must name a node with a parameter table (--list)");
  if (!update) {
    std::cout << ros_params::parameterBlock(node);
    return 0;
  }
  const std::string path = docs + "/" + node + ".md";
  std::ifstream in(path);
  if (!in) {
    std::cerr << "describe_parameters: cannot read " << path << "\n";
    return 1;
  }
  std::stringstream page;
  page << in.rdbuf();
  try {
    const std::string updated = ros_params::withParameterBlock(page.str(), node);
    io::writeTextFileAtomically(path, updated);
  } catch (const std::exception& e) {
    std::cerr << "describe_parameters: " << path << ": " << e.what() << "\n";
    return 1;
  }
  std::cout << "describe_parameters: " << path << " updated\n";
  return 0;
}
