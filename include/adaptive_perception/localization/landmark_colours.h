#pragma once
// Which half of the field, from the landmarks' colours alone: a pose against its point mirror.
//
// On a point-symmetric field a pose and its mirror see the same lines and, where the goals are
// alike (the SPL's white goals), the same goals; only the landmarks differ, and a landmark one
// pose sees, the other sees at the same pixels with other bands (pink over yellow against cyan
// over pink). The image likelihood weighs those few pixels by colour models that on a real camera
// come from other venues. This test asks the pixels' hue alone: each band the pose puts in the
// image (pixels where the pose's label and the mirror's differ) is compared with the hue of the
// pose's colour and of the mirror's. A pixel's hue is the direction of its chroma (U - 128,
// V - 128); its log-likelihood under a colour is concentration * cos(angle to the colour's hue)
// (a von Mises density over the hue angle), pixels paler than min_chroma saying nothing. Each band
// counts once (its pixels' mean: they see one surface and are not independent), so the evidence is
// in nats per band. Only the landmarks' pixels are rendered (their bounding boxes' images), so the
// test costs little at any image size.
//
// The colours' hues are those of typical paints (sRGB pink 255/105/180, yellow 255/255/0,
// sky-blue 80/160/230, green 0/160/0, orange 255/128/0, converted as color_space.h does); white
// and the background have none.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/world/label_renderer.h"

namespace adaptive_perception::localization {

struct LandmarkColourConfig {
  double concentration = 2.0;  // of the hue's von Mises density (nats per unit cosine)
  double min_chroma = 8.0;     // levels; paler pixels have no hue to speak of
  int min_band_pixels = 6;     // bands with fewer hued pixels in the image are not scored

  static const config::Fields<LandmarkColourConfig>& fields();
  void validate() const { fields().validate(*this); }
};

struct LandmarkColourEvidence {
  double mirror_minus_pose_nats = 0.0;  // > 0: the landmarks' hues favour the mirror
  int bands = 0;                        // bands scored
};

/// The evidence of the landmarks in `yuv` (CV_8UC3, the camera's full image) for the point mirror
/// of `pose` against `pose`; the camera at base_to_optical on the robot.
LandmarkColourEvidence landmarkMirrorEvidence(const cv::Mat& yuv,
                                              const world::LabelRenderer& renderer,
                                              const math::SE2& pose,
                                              const Eigen::Isometry3d& base_to_optical,
                                              const LandmarkColourConfig& config);

}  // namespace adaptive_perception::localization
