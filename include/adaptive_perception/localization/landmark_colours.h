#pragma once
// Which half of the field, from the landmarks' colours alone: a pose against its point mirror.
//
// On a point-symmetric field a pose and its mirror see the same lines and, where the goals are
// alike (the SPL's white goals), the same goals; only the landmarks differ: a landmark one pose
// sees, the other sees at the same pixels with the bands of the landmark at its point mirror (pink
// over yellow against cyan over pink). The image likelihood weighs those few pixels by colour
// models that on a real camera come from other venues. This test asks the pixels' hue alone.
//
// A pixel's similarity to a colour is the cosine between its chroma (U - 128, V - 128) and the
// colour's hue (0 for a pixel paler than min_chroma); a band's score is its pixels' mean, a
// template's the sum over its hued bands. Each landmark in view is found in a window around where
// the pose puts it (up to its width sideways, one and a half hued bands up or down: the pose is a
// few centimetres and degrees off, and one band's height is all that tells pink over cyan from cyan
// over pink), at the shift where its own bands or its mirror twin's fit best, a template counting
// only where its hued bands lie wholly in the image; both templates are
// scored at that one place (the two poses see the landmark at the same pixels; scored each at its
// own best shift, the mirror's pink band found the pose's pink band and fitted as well), and the
// evidence is concentration * (mirror's score - pose's score), summed over the landmarks seen
// (min_fit_share): in nats, the log-ratio of von Mises densities over the hue, one
// term per band (a band's pixels see one surface and are not independent).
//
// The colours' hues are those of typical paints (sRGB pink 255/105/180, yellow 255/255/0,
// sky-blue 80/160/230, green 0/160/0, orange 255/128/0, converted as color_space.h does); white
// and the background have none. Only the landmarks' windows are read, so the test costs little at
// any image size.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/world/label_renderer.h"

namespace adaptive_perception::localization {

struct LandmarkColourConfig {
  double concentration = 2.0;  // of the hue's von Mises density (nats per unit cosine)
  // Levels; paler pixels have no hue to speak of (a beige wall has 13 and looked yellow and pink
  // enough to win a landmark's mirror template on the NAO development images; the landmarks'
  // bands there have 22 to 40).
  double min_chroma = 15.0;
  // A landmark counts only where one of its templates fits at least this share as well as a
  // perfect one (the mean similarity of its hued bands): where the pose puts it on nothing like
  // it, both fit noise, and the difference of two noises is no evidence.
  double min_fit_share = 0.5;
  int min_band_pixels = 6;  // landmarks whose hued bands cover fewer pixels are not scored

  static const config::Fields<LandmarkColourConfig>& fields();
  void validate() const { fields().validate(*this); }
};

struct LandmarkColourEvidence {
  double mirror_minus_pose_nats = 0.0;  // > 0: the landmarks' hues favour the mirror
  int landmarks = 0;                    // landmarks scored
};

/// The evidence of the landmarks in `yuv` (CV_8UC3, the camera's full image) for the point mirror
/// of `pose` against `pose`; the camera at base_to_optical on the robot. std::invalid_argument for
/// an image of another type or size than the renderer's camera.
LandmarkColourEvidence landmarkMirrorEvidence(const cv::Mat& yuv,
                                              const world::LabelRenderer& renderer,
                                              const math::SE2& pose,
                                              const Eigen::Isometry3d& base_to_optical,
                                              const LandmarkColourConfig& config);

}  // namespace adaptive_perception::localization
