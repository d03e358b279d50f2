#include "adaptive_perception/ros/params.h"

#include <ros/package.h>

#include <fstream>

namespace adaptive_perception::ros_params {

std::string getName(const ros::NodeHandle& nh, const std::string& name, const std::string& def) {
  const std::string v = get<std::string>(nh, name, def);
  if (v.empty()) throw ParamError("parameter " + nh.resolveName(name) + " must not be empty");
  return v;
}

std::string resolvePackagePath(const std::string& value) {
  if (value.empty() || value[0] == '/' || std::ifstream(value).good()) return value;
  const std::string share = ros::package::getPath("adaptive_perception");
  if (!share.empty() && std::ifstream(share + "/" + value).good()) return share + "/" + value;
#ifdef AP_SOURCE_DIR
  // Tools run without a sourced workspace still find the package's files.
  const std::string source = std::string(AP_SOURCE_DIR) + "/" + value;
  if (std::ifstream(source).good()) return source;
#endif
  return value;
}

}  // namespace adaptive_perception::ros_params
