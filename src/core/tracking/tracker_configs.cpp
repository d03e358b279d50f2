// The field tables of the three trackers' configs (config/fields.h), as condensation_tracker's
// parameters name them: written once, for validate(), the node, the tools and the doc page.
#include "adaptive_perception/tracking/box_condensation_tracker.h"
#include "adaptive_perception/tracking/condensation_tracker.h"
#include "adaptive_perception/tracking/ellipse_tracker.h"

namespace adaptive_perception::tracking {

using config::closed;

const config::Fields<BoxTrackerConfig>& BoxTrackerConfig::fields() {
  using C = BoxTrackerConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("box_samples", &C::samples, closed(10, 100000), "mode box: samples N")
          .add("box_filter_gain", &C::filter_gain, closed(0, 1e4),
               "mode box: weight of the correlation filter's response (0: off)")
          .add("box_peak_fraction", &C::peak_fraction, closed(0, 0.99),
               "mode box: share of the samples drawn about the filter's peak")
          .add("box_lost_score", &C::lost_score, closed(-1, 1),
               "mode box: confidence below this is lost (searched for)")
          .add("box_reliable_peak_ratio", &C::reliable_peak_ratio, closed(0, 1),
               "mode box: a frame whose response peak (or APCE) and colour score fall below "
               "this share of their means is unreliable, reported lost (0: off)")
          .add("box_reliable_apce_ratio", &C::reliable_apce_ratio, closed(0, 1),
               "mode box: the same for the response's APCE (0: off)")
          .add("box_unreliable_stops_learning", &C::unreliable_stops_learning,
               "mode box: the models do not learn from an unreliable frame")
          .add("box_distractor_ratio", &C::distractor_ratio, closed(0, 1),
               "mode box: boxes around the target scoring this share of its colour score are "
               "distractors, whose colours count against the target's (0: off)")
          .add("box_distractor_scale", &C::distractor_scale, closed(1.5, 10),
               "mode box: how far distractors are looked for, in target sizes")
          .add("box_redetect_after_frames", &C::redetect_after_frames, closed(0, 1000),
               "mode box: after this many frames in a row reported lost, the whole frame is "
               "searched until the target is back (0: off)")
          .add("box_scale_filter_share", &C::scale_filter_share, closed(0, 1),
               "mode box: share of the estimate's log scale taken from a scale filter over 33 "
               "scales (DSST), the rest from the correlation filter's few (0: off)")
          .add("box_scale_learning_rate", &C::scale, &ScaleFilterConfig::learning_rate,
               closed(0, 1), "mode box: the scale filter's learning rate")
          .add("box_scale_padding", &C::scale, &ScaleFilterConfig::padding, closed(1, 5),
               "mode box: the scale filter's sample side / the target's side")
          .add("box_scale_model_area_px", &C::scale, &ScaleFilterConfig::model_area_px,
               closed(64, 65536), "mode box: the scale filter's patches' size (pixels)")
          .add("box_redetect_places", &C::redetect_places, closed(1, 100),
               "mode box: places of the target's colours the search gives to the filter");
  return f;
}

const config::Fields<CondensationConfig>& CondensationConfig::fields() {
  using C = CondensationConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("samples", &C::samples, closed(1, 100000), "modes condensation: samples N")
          .add("bins", &C::quantizer, &Quantizer::bins, closed(2, 64),
               "modes condensation and ellipse: histogram bins per colour channel")
          .add("contour_points", &C::contour_points, closed(8, 1000),
               "points of the affine snake")
          .add("sigma", &C::sigma, closed(1e-3, 100), "weight exp(-rho^2 / 2 sigma^2)")
          .add("lost_weight", &C::lost_weight, config::Range{0, 1, false, true},
               "best sample weight below this: the target is lost")
          .add("roi_margin", &C::roi_margin, closed(0, 20),
               "samples segment the predicted box grown by this times its size per side");
  return f;
}

const config::Fields<EllipseTrackerConfig>& EllipseTrackerConfig::fields() {
  using C = EllipseTrackerConfig;
  static const config::Fields<C> f =
      config::Fields<C>()
          .add("ellipse_search_radius_px", &C::search_radius_px, closed(1, 200),
               "mode ellipse: centres searched around the last one (px)")
          .add("ellipse_update_rate", &C::update_rate, closed(0, 1), "mode ellipse: a of eq. 29")
          .add("ellipse_update_threshold", &C::update_threshold, closed(0, 1),
               "mode ellipse: eq. 29 only above this histogram intersection")
          .add("ellipse_lost_threshold", &C::lost_threshold, closed(0, 1),
               "mode ellipse: below this intersection the target is lost");
  return f;
}

}  // namespace adaptive_perception::tracking
