#pragma once
// Reading the project's YAML files (worlds, priors) with messages that name the file and line.
#include <yaml-cpp/yaml.h>

#include <string>

namespace adaptive_perception::io {

/// Parses a YAML file. Throws std::runtime_error "PATH: cannot open WHAT" when it cannot be read
/// and "PATH:LINE: message" on a syntax error.
YAML::Node loadYamlFile(const std::string& path, const std::string& what);
/// Parses YAML text read from `source` (a file name, for messages). Throws std::runtime_error
/// "SOURCE:LINE: YAML syntax error: message" on a syntax error.
YAML::Node parseYamlText(const std::string& text, const std::string& source);
/// "PATH:LINE" of a node, for error messages.
std::string yamlWhere(const std::string& path, const YAML::Node& node);

}  // namespace adaptive_perception::io
