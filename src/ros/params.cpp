#include "adaptive_perception/ros/params.h"

#include <ros/package.h>

#include <filesystem>
#include <fstream>

namespace adaptive_perception::ros_params {

std::string getName(const ros::NodeHandle& nh, const std::string& name, const std::string& def) {
  const std::string v = get<std::string>(nh, name, def);
  if (v.empty()) throw ParamError("parameter " + nh.resolveName(name) + " must not be empty");
  return v;
}

std::string resolvePackagePath(const std::string& value) {
  if (value.empty() || value[0] == '/' || std::ifstream(value).good()) return value;
#ifdef AP_SOURCE_DIR
  // The source tree this build came from (so tools work without a sourced workspace, and rospack is
  // not asked, which prints errors when the package is not on ROS_PACKAGE_PATH).
  const std::string source = std::string(AP_SOURCE_DIR) + "/" + value;
  if (std::ifstream(source).good()) return source;
#endif
  const std::string share = ros::package::getPath("adaptive_perception");
  if (!share.empty() && std::ifstream(share + "/" + value).good()) return share + "/" + value;
  return value;
}

std::vector<color::LightingPrior> loadLightingPriors(const ros::NodeHandle& pnh,
                                                     std::string* filter, std::string* dir) {
  *filter = get<std::string>(pnh, "filter", "switching");
  std::vector<std::string> names;
  if (*filter == "switching") {
    names = get<std::vector<std::string>>(pnh, "priors", {"dark", "bright"});
  } else if (*filter == "single") {
    names = {get<std::string>(pnh, "single_prior", "all")};
  } else {
    throw ParamError("parameter " + pnh.resolveName("filter") + " = '" + *filter +
                     "' (allowed: switching, single)");
  }
  if (names.empty())
    throw ParamError("parameter " + pnh.resolveName("priors") + " must name at least one prior");
  *dir = resolvePackagePath(getName(pnh, "priors_dir", "config/color_priors"));
  std::vector<color::LightingPrior> priors;
  for (const auto& n : names)
    priors.push_back(
        color::LightingPrior::loadYaml((std::filesystem::path(*dir) / (n + ".yaml")).string()));
  return priors;
}

}  // namespace adaptive_perception::ros_params
