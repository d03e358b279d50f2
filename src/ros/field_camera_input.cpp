#include "adaptive_perception/ros/field_camera_input.h"

#include "adaptive_perception/ros/parameter_docs.h"
#include "adaptive_perception/ros/params.h"

namespace adaptive_perception::ros_conv {

FieldCameraInput::FieldCameraInput(const std::string& node, const ros::NodeHandle& pnh,
                                   double default_tf_timeout_s)
    : camera_(node, ros_params::get<std::string>(pnh, "camera_model", "")),
      tf_(node, pnh, default_tf_timeout_s),
      gate_(node, 0.0, ros_params::loadImageIntake(pnh), ImageGate::Output::kYuv),
      priors_(ros_params::loadLightingPriors(pnh, &filter_, &priors_dir_)),
      field_(ros_params::loadFieldMap(pnh)),
      map_frame_(ros_params::getFrameId(pnh, "map_frame", ros_topics::kMapFrame)),
      hints_(ros_params::imageTransportHints(pnh)) {}

std::vector<config::ParameterDoc> FieldCameraInput::parameters(double default_tf_timeout_s,
                                                               const std::string& tf_what) {
  return ros_params::joinRows(
      {{ros_params::fieldFileParameter(), CameraModelSource::parameter(),
        ros_params::frameParameter("map"), MeasurementTf::parameter(default_tf_timeout_s, tf_what)},
       ros_params::lightingPriorParameters(),
       ros_params::imageIntakeParameters()});
}

bool FieldCameraInput::readyFor(int width_px, int height_px) {
  if (camera_.readyFor(width_px, height_px)) return true;
  if (camera_.known()) ++bad_images_;  // the size disagrees with camera_info
  return false;
}

void FieldCameraInput::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) const {
  stat.add("frames skipped (no tf)", tf_.skipped());
  stat.add("frames dropped (older than the last)", gate_.outOfOrder());
  stat.add("frames skipped (bad image)", bad_images_ + gate_.badImages());
}

std::string FieldCameraInput::priorsSummary() const {
  return filter_ + " filter with " + std::to_string(priors_.size()) + " prior(s) from " +
         priors_dir_;
}

}  // namespace adaptive_perception::ros_conv
