// describe_parameters: prints a node's parameter table (every private parameter it reads, with its
// default, allowed range and what it does), as its doc page shows it; --update rewrites the table
// in docs/nodes/<node>.md (between its markers) from the code.
//
//   describe_parameters --help   (every option with its default, unit and range)
#include <fstream>
#include <iostream>
#include <sstream>

#include "adaptive_perception/io/atomic_file.h"
#include "adaptive_perception/ros/parameter_docs.h"
#include "command_line.h"

using namespace adaptive_perception;

int main(int argc, char** argv) {
  tools::CommandLine cli("describe_parameters",
                         "Prints a node's parameter table (every private parameter it reads, its "
                         "default, range and doc) as its doc page shows it; --update rewrites the "
                         "table in the page from the code.");
  bool list = false;
  cli.flag("list", &list, "list the nodes that have a table");
  std::string node;
  cli.option("node", &node, "the node");
  bool update = false;
  cli.flag("update", &update, "rewrite the table in DOCS/<node>.md (between its markers)");
  std::string docs = "docs/nodes";
  cli.option("docs", &docs, "folder of the nodes' doc pages");
  cli.parse(argc, argv);
  const auto& nodes = ros_params::nodeParameters();
  if (list) {
    for (const auto& [name, rows] : nodes) std::cout << name << " (" << rows.size() << ")\n";
    return 0;
  }
  if (!nodes.count(node)) cli.fail("--node must name a node with a parameter table (--list)");
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
