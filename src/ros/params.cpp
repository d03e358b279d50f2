#include "adaptive_perception/ros/params.h"

#include <ros/package.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "adaptive_perception/ros/topics.h"

namespace adaptive_perception::ros_params {

std::string getName(const ros::NodeHandle& nh, const std::string& name, const std::string& def) {
  const std::string v = get<std::string>(nh, name, def);
  if (v.empty()) throw ParamError("parameter " + nh.resolveName(name) + " must not be empty");
  return v;
}

std::string getFrameId(const ros::NodeHandle& nh, const std::string& name, const std::string& def) {
  const std::string v = getName(nh, name, def);
  const auto bad = std::find_if(v.begin(), v.end(), [](char ch) {
    return !(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.' ||
             ch == '/');
  });
  if (v[0] == '/' || bad != v.end() || v.find("//") != std::string::npos)
    throw ParamError("parameter " + nh.resolveName(name) + " = '" + v +
                     "' is not a tf frame id (no leading '/', no spaces; letters, digits and "
                     "_ - . / only)");
  return v;
}

namespace {
// The package's files as the running executable's location gives them: <dir>/../../share/
// adaptive_perception, or the source tree named in its source_dir.txt (devel space only).
std::string packageRootBesideExecutable() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return "";
  const fs::path share =
      exe.parent_path().parent_path().parent_path() / "share" / "adaptive_perception";
  std::ifstream named((share / "source_dir.txt").string());
  std::string source;
  if (named && std::getline(named, source) && !source.empty()) return source;
  return fs::exists(share / "package.xml", ec) ? share.string() : "";
}
}  // namespace

std::string resolvePackagePath(const std::string& value) {
  if (value.empty() || value[0] == '/' || std::ifstream(value).good()) return value;
  // Before rospack, which prints errors when the package is not on ROS_PACKAGE_PATH.
  static const std::string root = packageRootBesideExecutable();
  if (!root.empty() && std::ifstream(root + "/" + value).good()) return root + "/" + value;
  const std::string share = ros::package::getPath("adaptive_perception");
  if (!share.empty() && std::ifstream(share + "/" + value).good()) return share + "/" + value;
  return value;
}

namespace {
constexpr char kDefaultFilter[] = "switching", kDefaultPriorsDir[] = "config/color_priors";
}  // namespace

std::vector<config::ParameterDoc> lightingPriorParameters() {
  return {{"filter", "string", kDefaultFilter, "switching, single",
           "the lighting filter: switching between ~priors (a jump Markov model), or one "
           "~single_prior"},
          {"priors", "list", config::formatList(kDefaultSwitchingPriors), "",
           "the switching filter's lighting priors (names)"},
          {"single_prior", "string", kDefaultSinglePrior, "", "the single filter's prior"},
          {"priors_dir", "string", kDefaultPriorsDir, "",
           "where prior NAME is NAME.yaml (relative: the current directory, then the package)"}};
}

std::vector<color::LightingPrior> loadLightingPriors(const ros::NodeHandle& pnh,
                                                     std::string* filter, std::string* dir) {
  *filter = get<std::string>(pnh, "filter", kDefaultFilter);
  std::vector<std::string> names;
  if (*filter == "switching") {
    names = get<std::vector<std::string>>(pnh, "priors", kDefaultSwitchingPriors);
  } else if (*filter == "single") {
    names = {get<std::string>(pnh, "single_prior", kDefaultSinglePrior)};
  } else {
    throw ParamError("parameter " + pnh.resolveName("filter") + " = '" + *filter +
                     "' (allowed: switching, single)");
  }
  if (names.empty())
    throw ParamError("parameter " + pnh.resolveName("priors") + " must name at least one prior");
  *dir = resolvePackagePath(getName(pnh, "priors_dir", kDefaultPriorsDir));
  std::vector<color::LightingPrior> priors;
  for (const auto& n : names)
    priors.push_back(
        color::LightingPrior::loadYaml((std::filesystem::path(*dir) / (n + ".yaml")).string()));
  return priors;
}

std::vector<double> getNumbers(const ros::NodeHandle& nh, const std::string& name,
                               const std::vector<double>& def) {
  XmlRpc::XmlRpcValue v;
  if (!nh.getParam(name, v)) return def;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeString) {
    // rosrun's `_name:="[1, 2.5]"` arrives as a string: numbers separated by commas or spaces.
    std::string text = static_cast<std::string>(v);
    for (char& c : text)
      if (c == '[' || c == ']' || c == ',') c = ' ';
    std::istringstream in(text);
    std::vector<double> out;
    std::string word;
    while (in >> word) {
      std::size_t used = 0;
      double x = 0.0;
      try {
        x = std::stod(word, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != word.size())
        throw ParamError("parameter " + nh.resolveName(name) + ": '" + word + "' is not a number");
      out.push_back(x);
    }
    return out;
  }
  if (v.getType() != XmlRpc::XmlRpcValue::TypeArray)
    throw ParamError("parameter " + nh.resolveName(name) + " must be a list of numbers");
  std::vector<double> out;
  for (int i = 0; i < v.size(); ++i) {
    if (v[i].getType() == XmlRpc::XmlRpcValue::TypeInt)
      out.push_back(static_cast<int>(v[i]));
    else if (v[i].getType() == XmlRpc::XmlRpcValue::TypeDouble)
      out.push_back(static_cast<double>(v[i]));
    else
      throw ParamError("parameter " + nh.resolveName(name) + " entry " + std::to_string(i) +
                       " is not a number");
  }
  return out;
}

bool loadInitialPose(const ros::NodeHandle& pnh, const std::vector<double>& default_std,
                     math::SE2* pose, Eigen::Matrix3d* cov) {
  const auto initial = getNumbers(pnh, "initial_pose", {});
  const auto sd = getNumbers(pnh, "initial_pose_std", default_std);
  if (!initial.empty() && initial.size() != 3)
    throw ParamError("parameter " + pnh.resolveName("initial_pose") +
                     " must be [x_m, y_m, yaw_rad] or empty");
  if (sd.size() != 3 || !(sd[0] > 0) || !(sd[1] > 0) || !(sd[2] > 0))
    throw ParamError("parameter " + pnh.resolveName("initial_pose_std") +
                     " must be three positive standard deviations [x_m, y_m, yaw_rad]");
  *cov = Eigen::Vector3d(sd[0] * sd[0], sd[1] * sd[1], sd[2] * sd[2]).asDiagonal();
  if (initial.size() != 3) return false;
  *pose = math::SE2(initial[0], initial[1], initial[2]);
  return true;
}

namespace {
constexpr double kMinRestartBack_s = 0.01, kMaxRestartBack_s = 3600.0;
}

ros_conv::StampOrderConfig loadStampOrder(const ros::NodeHandle& pnh) {
  ros_conv::StampOrderConfig c;
  c.restart_after_back_s = getInRange(pnh, "time_back_restart_s", c.restart_after_back_s,
                                      kMinRestartBack_s, kMaxRestartBack_s);
  return c;
}

config::ParameterDoc frameParameter(const std::string& frame) {
  if (frame == "map") return {"map_frame", "string", ros_topics::kMapFrame, "", "the map frame"};
  if (frame == "odom")
    return {"odom_frame", "string", ros_topics::kOdomFrame, "", "the odometry frame"};
  if (frame == "base")
    return {"base_frame", "string", ros_topics::kBaseFrame, "", "the robot's frame"};
  throw std::invalid_argument("frameParameter: no frame '" + frame + "' (map, odom or base)");
}

namespace {
constexpr char kDefaultImageTransport[] = "raw";
}  // namespace

image_transport::TransportHints imageTransportHints(const ros::NodeHandle& pnh) {
  const std::string transport = get<std::string>(pnh, "image_transport", kDefaultImageTransport);
  return image_transport::TransportHints(transport, ros::TransportHints(), pnh);
}

namespace {
constexpr char kFieldFile[] = "config/field_4legged.yaml";
}  // namespace

world::FieldMap loadFieldMap(const ros::NodeHandle& pnh, std::string* path) {
  const std::string file = resolvePackagePath(getName(pnh, "field_file", kFieldFile));
  if (path) *path = file;
  return world::FieldMap::loadYaml(file);
}

config::ParameterDoc fieldFileParameter() {
  return {"field_file", "string", kFieldFile, "",
          "the field (YAML, format in docs/fields.md; shipped: config/field_4legged.yaml, "
          "config/field_spl.yaml, config/field_spl_landmarks.yaml); a relative path is looked up in "
          "the current directory, then in the package"};
}

config::ParameterDoc imageTransportParameter() {
  return {"image_transport", "string", kDefaultImageTransport, "raw, compressed",
          "the transport of camera/image_raw: raw, or compressed (camera/image_raw/compressed, "
          "JPEG or PNG)"};
}

namespace {
constexpr int kMaxImagePixelsLimit = 2'000'000'000;  // an XML-RPC int
}  // namespace

ros_conv::ImageIntakeConfig loadImageIntake(const ros::NodeHandle& pnh) {
  ros_conv::ImageIntakeConfig c;
  c.order = loadStampOrder(pnh);
  c.max_pixels =
      getInRange(pnh, "max_image_pixels", static_cast<int>(c.max_pixels), 1, kMaxImagePixelsLimit);
  return c;
}

std::vector<config::ParameterDoc> imageIntakeParameters() {
  const config::Range range = config::closed(1, kMaxImagePixelsLimit);
  return {stampOrderParameter(),
          {"max_image_pixels", "int", std::to_string(ros_conv::ImageIntakeConfig().max_pixels),
           range.text(),
           "an image (raw, or compressed before it is decoded) with more pixels (width x height) "
           "is dropped with an error"},
          imageTransportParameter()};
}

namespace {
constexpr int kDefaultSeed = 1, kMaxSeed = 1 << 30;
}  // namespace

std::uint64_t loadSeed(const ros::NodeHandle& pnh) {
  return static_cast<std::uint64_t>(getInRange(pnh, "seed", kDefaultSeed, 0, kMaxSeed));
}

config::ParameterDoc seedParameter() {
  return {"seed", "int", std::to_string(kDefaultSeed), config::closed(0, kMaxSeed).text(),
          "random seed: the same seed replays the same run"};
}

config::ParameterDoc stampOrderParameter() {
  const config::Range range = config::closed(kMinRestartBack_s, kMaxRestartBack_s);
  return {
      "time_back_restart_s", "double",
      config::formatValue(config::Kind::kDouble, ros_conv::StampOrderConfig().restart_after_back_s),
      range.text(),
      "an input older than the last is dropped; older by more than this (s), or the clock "
      "jumping back (a looped bag), restarts the node's estimate"};
}

}  // namespace adaptive_perception::ros_params
