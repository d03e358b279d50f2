#include "adaptive_perception/world/robot_camera.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "adaptive_perception/io/yaml_file.h"

namespace adaptive_perception::world {

namespace {

// The head chain's offsets are parts of one robot: beyond this, a slip of the file (mm for m).
constexpr double kMaxOffset_m = 10.0;

std::string at(const std::string& source, const YAML::Node& node) {
  return source + ":" + std::to_string(node.Mark().line + 1) + ": ";
}

}  // namespace

RobotCamera RobotCamera::loadYaml(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the camera file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parseYaml(ss.str(), path);
}

RobotCamera RobotCamera::parseYaml(const std::string& text, const std::string& source) {
  const YAML::Node root = io::parseYamlText(text, source);
  if (!root || root.IsNull()) throw std::runtime_error(source + ": no camera in the file (empty?)");
  if (!root.IsMap()) throw std::runtime_error(source + ": expected a map of camera keys");
  RobotCamera c;
  std::map<std::string, int*> ints = {{"width_px", &c.camera.width_px},
                                      {"height_px", &c.camera.height_px}};
  std::map<std::string, double*> numbers = {
      {"fx_px", &c.camera.fx_px},
      {"fy_px", &c.camera.fy_px},
      {"cx_px", &c.camera.cx_px},
      {"cy_px", &c.camera.cy_px},
      {"camera_pitch_rad", &c.head.camera_pitch_rad},
      {"min_pan_rad", &c.head.min_pan_rad},
      {"max_pan_rad", &c.head.max_pan_rad},
      {"min_tilt_rad", &c.head.min_tilt_rad},
      {"max_tilt_rad", &c.head.max_tilt_rad},
      {"torso_pitch_reference_rad", &c.head.torso_pitch_reference_rad},
  };
  std::map<std::string, Eigen::Vector3d*> vectors = {
      {"base_to_pan_m", &c.head.base_to_pan_m},
      {"pan_to_tilt_m", &c.head.pan_to_tilt_m},
      {"tilt_to_camera_m", &c.head.tilt_to_camera_m},
  };
  std::map<std::string, std::string*> strings = {
      {"name", &c.name}, {"pan_joint", &c.pan_joint}, {"tilt_joint", &c.tilt_joint}};
  bool intrinsics_given = false, size_given = false;
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>();
    const std::string where = at(source, kv.first);
    try {
      if (auto i = ints.find(key); i != ints.end()) {
        *i->second = kv.second.as<int>();
        size_given = true;
      } else if (auto n = numbers.find(key); n != numbers.end()) {
        const double v = kv.second.as<double>();
        if (!std::isfinite(v)) throw std::runtime_error(where + "'" + key + "' must be finite");
        // An angle beyond a full turn, or an offset on a robot beyond kMaxOffset_m, is a slip.
        if (key.size() > 4 && key.substr(key.size() - 4) == "_rad" && std::abs(v) > 2.0 * M_PI)
          throw std::runtime_error(where + "'" + key + "' must be within a full turn (rad)");
        *n->second = v;
        if (key.size() == 5 && key.substr(2) == "_px") intrinsics_given = true;
      } else if (auto v = vectors.find(key); v != vectors.end()) {
        const auto xyz = kv.second.as<std::vector<double>>();
        if (xyz.size() != 3 || !std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) ||
            !std::isfinite(xyz[2]))
          throw std::runtime_error(where + "'" + key + "' needs three finite numbers [x, y, z]");
        for (const double m : xyz)
          if (std::abs(m) > kMaxOffset_m)
            throw std::runtime_error(where + "'" + key + "' has an offset beyond " +
                                     std::to_string(int(kMaxOffset_m)) + " m");
        *v->second = {xyz[0], xyz[1], xyz[2]};
      } else if (auto s = strings.find(key); s != strings.end()) {
        *s->second = kv.second.as<std::string>();
        if (s->second->empty()) throw std::runtime_error(where + "'" + key + "' is empty");
      } else {
        throw std::runtime_error(where + "unknown key '" + key +
                                 "' (name, width_px, height_px, fx_px, fy_px, cx_px, cy_px, "
                                 "pan_joint, tilt_joint, base_to_pan_m, pan_to_tilt_m, "
                                 "tilt_to_camera_m, camera_pitch_rad, min_pan_rad, max_pan_rad, "
                                 "min_tilt_rad, max_tilt_rad, torso_pitch_reference_rad)");
      }
    } catch (const YAML::Exception& e) {
      throw std::runtime_error(where + "bad value for '" + key + "': " + e.msg);
    }
  }
  // A new image size with the AIBO's focal lengths would be a camera nobody has.
  if (size_given && !intrinsics_given)
    throw std::runtime_error(source +
                             ": width_px/height_px given without fx_px, fy_px, cx_px, "
                             "cy_px");
  if (c.head.min_pan_rad > c.head.max_pan_rad || c.head.min_tilt_rad > c.head.max_tilt_rad)
    throw std::runtime_error(source + ": a joint's min_*_rad is above its max_*_rad");
  try {
    c.camera.validate();
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(source + ": " + e.what());
  }
  return c;
}

}  // namespace adaptive_perception::world
