#pragma once
// The parameter tables of the nodes' doc pages. Each node that declares its parameters (a core
// Config's field table plus the node's own rows) is listed here; describe_parameters prints or
// rewrites the table in docs/nodes/<node>.md between the markers below, and
// parameters_documented_test checks that the page, the node's YAML and launch file and its source
// agree with it.
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

#include "adaptive_perception/config/fields.h"

namespace adaptive_perception::ros_params {

/// The rows of `parts`, one part after another: a node's table is made of its configs' rows, its
/// own and the shared ones (params.h).
std::vector<config::ParameterDoc> joinRows(
    std::initializer_list<std::vector<config::ParameterDoc>> parts);

/// Node name -> every private parameter it reads.
const std::map<std::string, std::vector<config::ParameterDoc>>& nodeParameters();

/// The doc-page block of a node's table, markers included.
std::string parameterBlock(const std::string& node);
/// `page` with its block for `node` replaced by parameterBlock(node); throws std::runtime_error
/// when the page has no such block (the markers: parameterBlockBegin / parameterBlockEnd).
std::string withParameterBlock(const std::string& page, const std::string& node);
std::string parameterBlockBegin(const std::string& node);
std::string parameterBlockEnd();

}  // namespace adaptive_perception::ros_params
