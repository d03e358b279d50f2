#pragma once
// Reading and validating private parameters. A node given a bad value refuses to start: the thrown
// ParamError names the parameter, the value and the allowed range.
#include <image_transport/transport_hints.h>
#include <ros/node_handle.h>

#include <Eigen/Core>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

#include "adaptive_perception/color/color_model.h"
#include "adaptive_perception/config/enum_names.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/localization/motion_model.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/ros/image_gate.h"
#include "adaptive_perception/ros/stamp_order.h"
#include "adaptive_perception/world/field_map.h"

namespace adaptive_perception::ros_params {

class ParamError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <typename T>
T get(const ros::NodeHandle& nh, const std::string& name, const T& def) {
  T value = def;
  if (nh.hasParam(name) && !nh.getParam(name, value)) {
    throw ParamError("parameter " + nh.resolveName(name) + " has the wrong type");
  }
  return value;
}

/// A number in [lo, hi].
template <typename T>
T getInRange(const ros::NodeHandle& nh, const std::string& name, const T& def, const T& lo,
             const T& hi) {
  const T v = get<T>(nh, name, def);
  if (!(v >= lo && v <= hi)) {
    std::ostringstream ss;
    ss << "parameter " << nh.resolveName(name) << " = " << v << " is out of range [" << lo << ", "
       << hi << "]";
    throw ParamError(ss.str());
  }
  return v;
}

/// Every field of a config's table that is set as a private parameter (others keep *config's
/// value): ints and bools must be given as such (a real may be given as an int). Throws ParamError
/// naming the parameter, its value and the allowed range.
template <class C>
void loadFields(const ros::NodeHandle& nh, const config::Fields<C>& fields, C* config) {
  for (const config::Field<C>& f : fields.all()) {
    if (!nh.hasParam(f.name)) continue;
    double v = 0.0;
    bool ok = false;
    if (f.kind == config::Kind::kInt) {
      int i = 0;
      ok = nh.getParam(f.name, i);
      v = i;
    } else if (f.kind == config::Kind::kBool) {
      bool b = false;
      ok = nh.getParam(f.name, b);
      v = b ? 1.0 : 0.0;
    } else {
      ok = nh.getParam(f.name, v);
    }
    if (!ok) {
      const char* want = f.kind == config::Kind::kInt    ? "an integer"
                         : f.kind == config::Kind::kBool ? "a boolean"
                                                         : "a number";
      throw ParamError("parameter " + nh.resolveName(f.name) + " has the wrong type (expected " +
                       want + ")");
    }
    if (!f.range.contains(v))
      throw ParamError("parameter " + nh.resolveName(f.name) + " = " +
                       config::formatValue(f.kind, v) + " is out of range " + f.range.text());
    f.set(*config, v);
  }
}

/// A parameter that takes one of a few words (config/enum_names.h); `def` when it is not set.
/// Throws ParamError naming the parameter, the word and the allowed ones.
template <class E>
E getWord(const ros::NodeHandle& nh, const std::string& name, const config::EnumNames<E>& words,
          E def) {
  const std::string word = get<std::string>(nh, name, words.name(def));
  try {
    return words.parse(word);
  } catch (const std::invalid_argument& e) {
    throw ParamError("parameter " + nh.resolveName(name) + ": " + e.what());
  }
}
/// Its row of a node's parameter table: the default's word and the allowed words.
template <class E>
config::ParameterDoc wordParameter(const std::string& name, const config::EnumNames<E>& words,
                                   E def, const std::string& doc) {
  return {name, "string", words.name(def), words.allowed(), doc};
}

/// A list of numbers; integers and reals may be mixed (YAML `[10, 20.5]`). Throws ParamError naming
/// the parameter when it is not a list of numbers.
std::vector<double> getNumbers(const ros::NodeHandle& nh, const std::string& name,
                               const std::vector<double>& def);

/// A file name or topic: must be non-empty.
std::string getName(const ros::NodeHandle& nh, const std::string& name, const std::string& def);

/// A tf frame id, checked at start-up as tf2 would check it later: non-empty, no leading '/', and
/// only letters, digits and `_ - . /` (no spaces).
std::string getFrameId(const ros::NodeHandle& nh, const std::string& name, const std::string& def);

/// A file of the package (e.g. "config/field_4legged.yaml") when `value` is relative and not found
/// from the current directory; `value` itself otherwise. Looked for, in order, beside the running
/// executable: an installed one (<prefix>/lib/adaptive_perception/) finds its share directory
/// (<prefix>/share/adaptive_perception/), a devel-space one the source tree that the build wrote
/// into devel/share/adaptive_perception/source_dir.txt (so that tools run without a sourced
/// workspace); then rospack's path of the package. Nothing of the source tree is compiled in.
std::string resolvePackagePath(const std::string& value);

/// The priors a colour node runs on when ~priors / ~single_prior are not set.
inline const std::vector<std::string> kDefaultSwitchingPriors = {"dark", "bright"};
inline const std::string kDefaultSinglePrior = "all";

/// The lighting priors a colour node runs on, from ~filter (switching: the ~priors list; single:
/// ~single_prior) and ~priors_dir (YAML files NAME.yaml). Returns the priors and sets *filter and
/// *dir; throws ParamError on a bad ~filter or empty list, std::runtime_error on a bad prior file.
std::vector<color::LightingPrior> loadLightingPriors(const ros::NodeHandle& pnh,
                                                     std::string* filter, std::string* dir);

/// The planar pose ~initial_pose ([x_m, y_m, yaw_rad]) and ~initial_pose_std (three positive
/// standard deviations). Returns false when ~initial_pose is empty or unset (then *pose is left);
/// throws ParamError on a wrong length or a non-positive deviation.
bool loadInitialPose(const ros::NodeHandle& pnh, const std::vector<double>& default_std,
                     math::SE2* pose, Eigen::Matrix3d* cov);

/// ~time_back_restart_s (ros_conv::StampOrderConfig: how far back a stamp must go to restart).
ros_conv::StampOrderConfig loadStampOrder(const ros::NodeHandle& pnh);
/// Its row in a node's parameter table (ros/parameter_docs.h).
config::ParameterDoc stampOrderParameter();
/// The row of ~map_frame, ~odom_frame or ~base_frame (`frame`: "map", "odom" or "base") with the
/// project's name for that frame (ros/topics.h) as its default.
config::ParameterDoc frameParameter(const std::string& frame);
/// How an image node takes its camera images: ~image_transport names the transport (raw, the
/// default, or compressed: ros/compressed_transport.h, or any plugin installed), as
/// image_transport's own nodes read it. Throws ParamError naming a transport that is not installed.
image_transport::TransportHints imageTransportHints(const ros::NodeHandle& pnh);
config::ParameterDoc imageTransportParameter();
/// An image node's intake (ros_conv::ImageGate): ~time_back_restart_s and ~max_image_pixels.
ros_conv::ImageIntakeConfig loadImageIntake(const ros::NodeHandle& pnh);
/// The rows of an image node's intake: ~time_back_restart_s, ~max_image_pixels and
/// ~image_transport.
std::vector<config::ParameterDoc> imageIntakeParameters();
/// ~seed of a node that samples (default 1, [0, 2^30]): the same seed replays the same run.
std::uint64_t loadSeed(const ros::NodeHandle& pnh);
config::ParameterDoc seedParameter();
/// The field of ~field_file (YAML; default config/field_4legged.yaml, a relative path looked up in
/// the current directory, then in the package); *path, when given, is set to the file read.
/// Throws std::runtime_error naming a file that cannot be read or parsed.
world::FieldMap loadFieldMap(const ros::NodeHandle& pnh, std::string* path = nullptr);
config::ParameterDoc fieldFileParameter();
/// The rows of the parameters loadLightingPriors reads (~filter, ~priors, ~single_prior,
/// ~priors_dir).
std::vector<config::ParameterDoc> lightingPriorParameters();

}  // namespace adaptive_perception::ros_params
