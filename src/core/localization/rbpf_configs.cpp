// The field tables (config/fields.h) of the RBPF localizer's config and of its parts', as
// rbpf_localizer's parameters name them: written once, for validate(), the node,
// evaluate_localization and the doc page. The node's parameters are one flat namespace, so the
// parts' names stand together here (Fields refuses a name declared twice).
#include "adaptive_perception/localization/global_localization.h"
#include "adaptive_perception/localization/goal_detection.h"
#include "adaptive_perception/localization/image_likelihood.h"
#include "adaptive_perception/localization/landmark_colours.h"
#include "adaptive_perception/localization/mirror_test.h"
#include "adaptive_perception/localization/motion_model.h"
#include "adaptive_perception/localization/pose_search.h"
#include "adaptive_perception/localization/rbpf_localizer.h"
#include "adaptive_perception/localization/relocalization_monitor.h"

namespace adaptive_perception::localization {

const config::Fields<RbpfConfig>& RbpfConfig::fields() {
  using C = RbpfConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("particles", &C::particles, config::closed(1, 1000000), "number of particles")
          .add("resample_ess_fraction", &C::resample_ess_fraction, config::aboveZero(1),
               "resample when the effective sample size falls below this share of the particles")
          .add("mirror_fraction", &C::mirror_fraction, config::closed(0, 0.5),
               "share of the particles replaced by point mirrors of others at each resampling")
          .add("mirror_relative_weight", &C::mirror_relative_weight, config::aboveZero(1),
               "a mirrored particle's weight relative to the others")
          .add("drift_std_per_sqrt_s", &C::model, &color::ColorModelConfig::drift_std_per_sqrt_s,
               config::closed(0, 100), "lighting drift of each particle's filter (levels/sqrt(s))")
          .add("mode_stay_probability", &C::switching,
               &color::SwitchingFilterConfig::mode_stay_probability, config::closed(1e-3, 1),
               "probability that the lighting stays in its mode from one image to the next")
          .add("goal_pitch_correction", &C::goal_pitch_correction,
               "the body lean a goal seen at a global start measures is added to the head "
               "chain's camera pose until the particles are placed anew (a global start or an "
               "initial pose)")
          .add("adapt_priors_to_image", &C::adapt_priors_to_image,
               "the priors are adapted to the first image after a start, without a pose (a "
               "camera at a venue the priors were not learnt from, such as a real robot's)")
          .add("balance_to_paint", &C::balance_to_paint,
               "with adapt_priors_to_image, every image until the particles are placed anew is "
               "balanced so that the first image's line paint is grey at white_balance_paint_luma")
          .add("balance_retry_images", &C::balance_retry_images, config::closed(0, 1000000),
               "when the adapted-to image gave no white balance, another image is tried every "
               "this many images (0: never)")
          .nest(&C::white_balance, color::WhiteBalanceConfig::fields())
          .nest(&C::likelihood, ImageLikelihoodConfig::fields())
          .nest(&C::motion, MotionModelConfig::fields())
          .nest(&C::search, PoseSearchConfig::fields())
          .nest(&C::global, GlobalLocalizationConfig::fields())
          .nest(&C::relocalization, RelocalizationConfig::fields())
          .nest(&C::mirror_test, MirrorTestConfig::fields())
          .nest(&C::goals, GoalDetectionConfig::fields())
          .nest(&C::circle, CentreCircleConfig::fields());
  return f;
}

const config::Fields<ImageLikelihoodConfig>& ImageLikelihoodConfig::fields() {
  using C = ImageLikelihoodConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("pixel_stride", &C::pixel_stride, config::closed(1, 256),
               "every stride-th pixel in x and y is scored (px of a reference_width_px-wide image)")
          .add("outlier_probability", &C::outlier_probability, config::belowOne(),
               "weight of the uniform density in each pixel's likelihood")
          .add("exponent", &C::exponent, config::aboveZero(1),
               "the image log-likelihood is multiplied by this (scaled by the grid's pixel count)")
          .add("position_tolerance_m", &C::position_tolerance_m, config::closed(0, 1),
               "a pixel's predicted colour is blurred over where a pose error this size moves it "
               "(m)")
          .add("heading_tolerance_rad", &C::heading_tolerance_rad, config::closed(0, 0.5),
               "the same for a heading error (rad)")
          .add("pitch_tolerance_rad", &C::pitch_tolerance_rad, config::closed(0, 0.2),
               "the same for an error of the camera's pitch (rad; 0: the pitch is known)")
          .add("max_neighbourhood_cells", &C::max_neighbourhood_cells, config::closed(0, 16),
               "at most this many grid steps of blur")
          .add("reference_width_px", &C::reference_width_px, config::closed(16, 10000),
               "the strides are in pixels of an image this wide; other cameras are scaled")
          .add("background_from_image", &C::background_from_image,
               "a pixel the map shows as background scores the density of the image's own "
               "colours above the field's boundary (pose-free segmentation), not the uniform one")
          .add("background_width_px", &C::background_width_px, config::closed(64, 10000),
               "that segmentation runs on the image shrunk to at most this width (px)");
  return f;
}

const config::Fields<MotionModelConfig>& MotionModelConfig::fields() {
  using C = MotionModelConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("odom_alpha1", &C::alpha1, config::closed(0, 10),
               "rotation noise per radian of rotation")
          .add("odom_alpha2", &C::alpha2, config::closed(0, 10),
               "rotation noise (rad) per metre of translation")
          .add("odom_alpha3", &C::alpha3, config::closed(0, 10),
               "translation noise per metre of translation")
          .add("odom_alpha4", &C::alpha4, config::closed(0, 10),
               "translation noise (m) per radian of rotation")
          .add("odom_min_translation_std_m", &C::min_translation_std_m, config::closed(0, 1),
               "translation noise floor per step (m), so that particles never collapse")
          .add("odom_min_rotation_std_rad", &C::min_rotation_std_rad, config::closed(0, 1),
               "rotation noise floor per step (rad)");
  return f;
}

const config::Fields<PoseSearchConfig>& PoseSearchConfig::fields() {
  using C = PoseSearchConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("free_space_margin_m", &C::free_space_margin_m, config::closed(0, 2),
               "uniform poses are drawn this far from walls and goals (m)")
          .add("global_pixel_stride", &C::pixel_stride, config::closed(1, 256),
               "the searches score every stride-th pixel (px of a reference_width_px-wide image)")
          .add("refine_rounds", &C::refine_rounds, config::closed(0, 20),
               "hill-climbing rounds on a search's best poses (0: off)")
          .add("refine_tries", &C::refine_tries, config::closed(0, 1000),
               "perturbations a pose and round")
          .add("refine_sigma_m", &C::refine_sigma_m, config::closed(0, 5),
               "first round's perturbation (m), halved every round")
          .add("refine_sigma_rad", &C::refine_sigma_rad, config::closed(0, 3.2),
               "first round's perturbation (rad), halved every round");
  return f;
}

const config::Fields<GlobalLocalizationConfig>& GlobalLocalizationConfig::fields() {
  using C = GlobalLocalizationConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("global_pool_size", &C::pool_size, config::closed(0, 10000000),
               "uniform poses the global search scores (0: no search, the particles as drawn)")
          .add("global_search_frames", &C::search_frames, config::closed(1, 100),
               "images scored before the particles commit (also the relocalization check's)")
          .add(
              "global_confirm_frames", &C::confirm_frames, config::closed(0, 100),
              "the pool goes on to this image, then the second draw (<= global_search_frames: off)")
          .add("global_confirm_fraction", &C::confirm_fraction, config::closed(0, 1),
               "share of the particles drawn again from the pool at the second draw")
          .add("refine_candidates", &C::refine_candidates, config::closed(0, 1000000),
               "best poses refined at the commit and at the second draw")
          .add("global_goal_pool_share", &C::goal_pool_share, config::closed(0, 1),
               "share of the global search's pool (and of a relocalization check's) drawn from "
               "the goals its first image shows")
          .add("global_goal_pool_size", &C::goal_pool_size, config::closed(2, 10000000),
               "poses a global search scores when its first image shows a goal")
          .add("global_goal_pixel_stride", &C::goal_pixel_stride, config::closed(1, 256),
               "that search's grid: every stride-th pixel (px of a reference_width_px-wide image)");
  return f;
}

const config::Fields<RelocalizationConfig>& RelocalizationConfig::fields() {
  using C = RelocalizationConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("relocalization_interval_s", &C::interval_s, config::closed(0, 1e6),
               "a check that the particles are not lost every this many seconds (0: off)")
          .add("relocalization_pool_size", &C::pool_size, config::closed(0, 10000000),
               "poses a check scores beside the particles (around a goal in view, else uniform)")
          .add("relocalization_margin", &C::margin, config::closed(-1e6, 1e6),
               "the check's best pose must beat the particles' by this (tempered nats)")
          .add("relocalization_fraction", &C::fraction, config::aboveZero(1),
               "share of the particles drawn from the check's poses (relocalization_restart false)")
          .add("relocalization_restart", &C::restart,
               "a check that wins restarts the global search (else: the draw above)")
          .add("relocalization_refine_candidates", &C::refine_candidates,
               config::closed(0, 1000000), "best poses refined on each side of a check");
  return f;
}

const config::Fields<MirrorTestConfig>& MirrorTestConfig::fields() {
  using C = MirrorTestConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("mirror_test_margin_nats", &C::margin_nats, config::closed(0, 1e6),
               "the particles move to their mirrors when the evidence exceeds this (0: off)")
          .add("mirror_test_memory_s", &C::memory_s, config::aboveZero(1e6),
               "time constant of the evidence's fading (s)")
          .add("mirror_test_view_interval_s", &C::view_interval_s, config::aboveZero(60),
               "images closer in time than this count as a share of one view (s)")
          .nest(&C::landmarks, LandmarkColourConfig::fields());
  return f;
}

}  // namespace adaptive_perception::localization
