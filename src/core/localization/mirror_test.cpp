#include "adaptive_perception/localization/mirror_test.h"

#include <algorithm>
#include <cmath>

#include "adaptive_perception/world/color_class.h"

namespace adaptive_perception::localization {

MirrorTest::MirrorTest(const std::vector<color::LightingPrior>& priors,
                       const color::ColorModelConfig& model,
                       const color::SwitchingFilterConfig& switching,
                       const MirrorTestConfig& config)
    : config_(config), model_(model), lighting_(priors, model, switching) {
  config_.validate();
}

void MirrorTest::reset() {
  have_pose_ = false;
  evidence_ = 0.0;
  lighting_.reset();
}

MirrorTest::Result MirrorTest::observe(const math::SE2& pose, const math::SE2& odom_delta,
                                       double dt_s, bool restart, const ImageLikelihood& likelihood,
                                       const SampledImage& image, const cv::Mat& yuv,
                                       const Eigen::Isometry3d& base_to_optical) {
  Result result;
  if (config_.margin_nats <= 0.0) return result;
  if (restart) have_pose_ = false;
  if (!have_pose_) evidence_ = 0.0;
  if (have_pose_) {
    // (Starting again on the move to the other cluster as well cost the bright bag: the estimate
    // went back and forth between the clusters, and converged seconds later.)
    const math::SE2 predicted = pose_ * odom_delta;
    constexpr double kJumpM = 0.5;
    const math::SE2 other = math::pointMirror(predicted);
    if (std::hypot(pose.x_m - predicted.x_m, pose.y_m - predicted.y_m) > kJumpM) {
      if (std::hypot(pose.x_m - other.x_m, pose.y_m - other.y_m) <= kJumpM)
        evidence_ = -evidence_;
      else
        evidence_ = 0.0;
    }
  }
  const double dt = std::max(dt_s, 0.0);
  lighting_.predict(dt);
  color::ColorObservation obs;
  const double ll_pose =
      likelihood.logLikelihood(image, pose, lighting_, base_to_optical, &obs, nullptr);
  const double ll_mirror = likelihood.logLikelihood(image, math::pointMirror(pose), lighting_,
                                                    base_to_optical, nullptr, nullptr);
  double hues = 0.0;
  const world::FieldDimensions& field = likelihood.map().dimensions();
  if (config_.landmarks.concentration > 0.0 &&
      field.goal_color_minus_x == field.goal_color_plus_x) {
    hues = landmarkMirrorEvidence(yuv, likelihood.renderer(), pose, base_to_optical,
                                  config_.landmarks)
               .mirror_minus_pose_nats;
  }
  const double view_share = dt > 0.0 ? std::min(1.0, dt / config_.view_interval_s) : 1.0;
  evidence_ = evidence_ * std::exp(-dt / config_.memory_s) +
              view_share * (ll_mirror - ll_pose + hues);
  // Only the colours that look alike from both poses teach the reference lighting.
  const auto& classes = model_.classes;
  for (std::size_t k = 0; k < obs.counts.size() && k < classes.size(); ++k)
    if (classes[k] != world::kGreen && classes[k] != world::kWhite) obs.counts[k] = 0;
  lighting_.update(obs);
  pose_ = pose;
  have_pose_ = true;
  if (evidence_ > config_.margin_nats) {
    pose_ = math::pointMirror(pose);
    evidence_ = -evidence_;
    result.flip = true;
  }
  result.evidence = evidence_;
  return result;
}

}  // namespace adaptive_perception::localization
