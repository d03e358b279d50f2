// Every node with a parameter table (ros/parameter_docs.h): its doc page shows the table the code
// makes, its YAML sets only parameters the node reads and only where they differ from the
// defaults, its launch file sets only parameters the node reads, and every name the node's source
// reads by hand is in the table (and every row of the table not from a config is read). No master
// is needed.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "adaptive_perception/ros/parameter_docs.h"

using namespace adaptive_perception;

namespace {
std::string read(const std::string& relative) {
  std::ifstream in(std::string(AP_SOURCE_DIR) + "/" + relative);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::set<std::string> names(const std::vector<config::ParameterDoc>& rows) {
  std::set<std::string> out;
  for (const auto& r : rows) out.insert(r.name);
  return out;
}

// The string literals a source passes as a parameter name: `(pnh, "name"` and
// `resolveName("name")`.
std::set<std::string> namesReadIn(const std::string& source) {
  std::set<std::string> out;
  const std::regex read(R"(\(\s*pnh\s*,\s*"([A-Za-z0-9_]+)\")");
  for (auto it = std::sregex_iterator(source.begin(), source.end(), read);
       it != std::sregex_iterator(); ++it)
    out.insert((*it)[1]);
  return out;
}
}  // namespace

TEST(ParametersDocumented, TheDocPageShowsTheTableTheCodeMakes) {
  for (const auto& [node, rows] : ros_params::nodeParameters()) {
    const std::string page = read("docs/nodes/" + node + ".md");
    ASSERT_FALSE(page.empty()) << "docs/nodes/" << node << ".md";
    EXPECT_NE(page.find(ros_params::parameterBlock(node)), std::string::npos)
        << "docs/nodes/" << node << ".md: the parameter table is not the code's; run "
        << "describe_parameters --node " << node << " --update";
  }
}

TEST(ParametersDocumented, YamlSetsOnlyReadParametersAndOnlyWhereTheyDiffer) {
  for (const auto& [node, rows] : ros_params::nodeParameters()) {
    const std::string path = std::string(AP_SOURCE_DIR) + "/config/" + node + ".yaml";
    const YAML::Node yaml = YAML::LoadFile(path);
    if (!yaml.IsMap()) continue;  // nothing overridden
    for (const auto& kv : yaml) {
      const std::string key = kv.first.as<std::string>();
      const auto row = std::find_if(rows.begin(), rows.end(),
                                    [&](const config::ParameterDoc& r) { return r.name == key; });
      ASSERT_NE(row, rows.end()) << path << ": " << key << " is not a parameter of " << node;
      if (kv.second.IsScalar()) {
        const std::string value = kv.second.as<std::string>();
        char* end_a = nullptr;
        char* end_b = nullptr;
        const double a = std::strtod(value.c_str(), &end_a);
        const double b = std::strtod(row->default_value.c_str(), &end_b);
        const bool numbers = *end_a == '\0' && *end_b == '\0' && !value.empty();
        EXPECT_FALSE(numbers ? a == b : value == row->default_value)
            << path << ": " << key << " repeats the default (only overrides belong here)";
      }
    }
  }
}

TEST(ParametersDocumented, LaunchFileSetsOnlyReadParameters) {
  for (const auto& [node, rows] : ros_params::nodeParameters()) {
    const std::string launch = read("launch/" + node + ".launch");
    ASSERT_FALSE(launch.empty()) << "launch/" << node << ".launch";
    const std::set<std::string> known = names(rows);
    const std::regex param(R"(<(?:param|rosparam)[^>]*?\s(?:name|param)="([A-Za-z0-9_]+)\")");
    for (auto it = std::sregex_iterator(launch.begin(), launch.end(), param);
         it != std::sregex_iterator(); ++it) {
      EXPECT_TRUE(known.count((*it)[1])) << "launch/" << node << ".launch sets " << (*it)[1]
                                         << ", which " << node << " does not read";
    }
  }
}

TEST(ParametersDocumented, EveryNameTheSourceReadsIsDocumentedAndEveryNodeRowIsRead) {
  // The shared readers count as the node's: params.cpp (priors, field, initial pose, stamp
  // order), the field camera's input (camera model, map frame) and the tf lookups (timeout).
  const std::string shared = read("src/ros/params.cpp") + read("src/ros/field_camera_input.cpp") +
                             read("src/ros/measurement_tf.cpp");
  for (const auto& [node, rows] : ros_params::nodeParameters()) {
    const std::string source = read("src/ros/" + node + "_node.cpp");
    ASSERT_FALSE(source.empty());
    const std::set<std::string> known = names(rows);
    for (const std::string& n : namesReadIn(source)) {
      EXPECT_TRUE(known.count(n)) << "src/ros/" << node << "_node.cpp reads ~" << n
                                  << ", which its table does not document";
    }
    const std::set<std::string> read_here = namesReadIn(source), read_shared = namesReadIn(shared);
    bool any_config = false;
    for (const auto& r : rows) {
      any_config |= r.in_config;
      if (!r.in_config) {
        EXPECT_TRUE(read_here.count(r.name) || read_shared.count(r.name))
            << node << " documents ~" << r.name << " but does not read it";
      }
    }
    if (any_config) {
      EXPECT_NE(source.find("loadFields("), std::string::npos)
          << "src/ros/" << node << "_node.cpp does not load its config's table";
    }
  }
}

// A numeric range as the tables write it: "[lo, hi]", "(lo, hi]", "[lo, hi)".
static bool parseRange(const std::string& text, double* lo, double* hi) {
  static const std::regex range(R"(^[\[\(]\s*([-+0-9.eE]+)\s*,\s*([-+0-9.eE]+)\s*[\]\)]$)");
  std::smatch m;
  if (!std::regex_match(text, m, range)) return false;
  *lo = std::stod(m[1]);
  *hi = std::stod(m[2]);
  return true;
}

TEST(ParametersDocumented, DynamicReconfigureAgreesWithTheTable) {
  // Each .cfg entry: gen.add("name", type_t, level, "doc", default[, min, max]). The default must
  // be the table's, and the slider's span must lie within the range the node accepts.
  const std::regex add(
      R"re(gen\.add\("(\w+)",\s*(\w+)_t,\s*\d+,\s*"[^"]*",\s*([^,\)]+)(?:,\s*([^,\)]+),\s*([^,\)]+))?\))re");
  const std::map<std::string, std::string> files = {{"cfg/LineExtractor.cfg", "line_extractor"},
                                                    {"cfg/ColorEstimator.cfg", "color_estimator"}};
  for (const auto& [file, node] : files) {
    const std::string cfg = read(file);
    ASSERT_FALSE(cfg.empty()) << file;
    const auto& rows = ros_params::nodeParameters().at(node);
    int entries = 0;
    for (auto it = std::sregex_iterator(cfg.begin(), cfg.end(), add); it != std::sregex_iterator();
         ++it, ++entries) {
      const std::string name = (*it)[1], type = (*it)[2], def = (*it)[3];
      const auto row = std::find_if(rows.begin(), rows.end(),
                                    [&](const config::ParameterDoc& r) { return r.name == name; });
      ASSERT_NE(row, rows.end()) << file << " tunes ~" << name << ", which " << node
                                 << "'s table does not have";
      if (type == "double" || type == "int") {
        EXPECT_DOUBLE_EQ(std::stod(def), std::stod(row->default_value))
            << file << ": default of " << name;
        double lo = 0, hi = 0;
        if ((*it)[4].matched && parseRange(row->range, &lo, &hi)) {
          EXPECT_GE(std::stod((*it)[4]), lo) << file << ": slider of " << name << " below "
                                             << row->range;
          EXPECT_LE(std::stod((*it)[5]), hi) << file << ": slider of " << name << " above "
                                             << row->range;
        }
      } else if (type == "bool") {
        EXPECT_EQ(def == "True" ? "true" : "false", row->default_value)
            << file << ": default of " << name;
      } else {
        EXPECT_EQ(def, "\"" + row->default_value + "\"") << file << ": default of " << name;
      }
    }
    EXPECT_GT(entries, 0) << file << " has no gen.add line this test can read";
  }
}
