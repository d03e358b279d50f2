#pragma once
// The centre circle seen in a camera image, and the robot poses it puts the robot at: proposals
// for the global search where no goal is in view (the NAO development point punt3 sees the
// circle and the halfway line, and no goal).
//
// Contract: detectCentreCircle() takes the pose-free segmentation's line pixels with carpet
// above them (not a post's white; a landmark's white base under a green band passes, see
// docs/field_localization.md), puts each on the ground under the head chain's
// camera (base_link; the robot's pose on the field is not needed), and looks for a circle of the
// field's centre-circle radius through them (RANSAC over pairs of points, then least squares on its
// inliers). A circle is kept only when its inliers cover one arc (gaps up to max_arc_gap_rad
// bridged) of min_arc_over_line times the arc a straight line fits: a line stays within t of a
// circle of radius R (on either side) over 4 sqrt(t / R) radians (1.13 rad for R = 0.75 m, t = 0.06
// m), and where the circle lies in view at least min_painted_share of it is paint. A circle whose
// arc would have to exceed half of it is too small for the tolerance and is not looked for (the
// four-legged field's, R = 0.18 m: 3.2 rad). The halfway line is then the line through the circle's
// centre along which the remaining line points fill the longest stretch. centreCirclePoses() turns
// a sighting into robot poses: with the halfway line, two (a point-mirrored pair: which half the
// robot is in is for the landmarks to decide); without it, a ring of headings about the centre.
// Fields without a centre circle get nothing.
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "adaptive_perception/color/field_segmentation.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/world/camera_model.h"
#include "adaptive_perception/world/field_map.h"

namespace adaptive_perception::localization {

struct CentreCircleConfig {
  // Line pixels farther than this on the ground are left out: a pixel row there spans more than
  // the tolerance below (a 640 x 480 NAO camera 0.5 m up: one row is 6 cm at 3 m).
  double max_range_m = 3.0;
  // A line point fits the circle (the halfway line) when it lies within this of it: the line's
  // half width (0.025 m on the SPL field) plus a pixel row's ground span at mid range.
  double inlier_tolerance_m = 0.06;
  // The halfway line: at least this many metres of it (its points' extent along it) on the
  // inliers of a line through the circle's centre.
  double min_halfway_length_m = 0.5;
  // Where the circle lies in view (in the image, within max_range_m), at least this share of it
  // must be paint: line fragments can fill a wide arc of a circle that is not there (a circle
  // through the corner of two lines), and then most of that circle is carpet. Half: robots and
  // balls on the circle, and paint the segmentation missed, cost a painted circle less than
  // that; fragments fill little of a false one.
  double min_painted_share = 0.5;
  // The inliers' arc over the widest a straight line fits (above): 1.4 asks for 1.6 rad (92
  // degrees) on the SPL field. Twice (2.26 rad) would miss the circle the NAO's top camera sees
  // from 1-2 m beside it (punt3, and rendered views of that kind in centre_circle_test): its near
  // side lies below the image. The paint check and the RANSAC score (the arc in view the inliers
  // miss counts against a candidate) refuse what a lower bar lets through.
  double min_arc_over_line = 1.4;
  // ... as one arc, gaps up to this wide bridged: a ball (0.1 m) on the line hides 7.6 degrees of
  // the SPL circle; 10 degrees. Two straight lines through a circle that is not there fill two
  // short arcs.
  double max_arc_gap_rad = 0.175;
  // ... counting only where the circle's paint is at least this many pixels across in the image:
  // thinner, the segmentation does not resolve it (the far side of the circle seen from its near
  // side: 0.05 m of paint 3 m from a camera 0.5 m up spans 1.6 rows of a 640 x 480 NAO image).
  double min_line_width_px = 2.0;
  // Every this many pixels in x and y is a line pixel looked at (of a 640-wide image; scaled).
  int pixel_stride = 2;
  // RANSAC draws (pairs of points).
  int iterations = 400;
  // Uncertainty of the poses centreCirclePoses() draws around a sighting.
  double position_sd_m = 0.1;
  double heading_sd_rad = 0.05;

  static const config::Fields<CentreCircleConfig>& fields();
  void validate() const { fields().validate(*this); }
};

struct CentreCircleSighting {
  Eigen::Vector2d centre_m{0, 0};  // base_link
  double arc_rad = 0.0;  // the longest arc its inliers cover (gaps up to max_arc_gap_rad bridged)
  double painted_share = 0.0;  // of the circle in view, the share that is paint
  int inliers = 0;
  // The halfway line's direction in base_link (radians, modulo pi), when seen.
  std::optional<double> halfway_direction_rad;
};

/// Whether the map's centre circle is large enough for the tolerance to be found (see above).
bool centreCircleFindable(const world::FieldMap& map, const CentreCircleConfig& config);

/// The centre circle in the segmentation's line pixels, with the camera at `base_to_optical`
/// on the robot (base_link -> camera_optical_frame); none when the field has no centre circle or
/// no wide enough arc is seen. `seed` makes the RANSAC draws reproducible.
std::optional<CentreCircleSighting> detectCentreCircle(const color::FieldSegmentation& segmentation,
                                                       const world::PinholeCamera& camera,
                                                       const Eigen::Isometry3d& base_to_optical,
                                                       const world::FieldMap& map,
                                                       const CentreCircleConfig& config,
                                                       std::uint64_t seed);

/// At most `count` robot poses (map -> base_link) drawn around the sighting, in point-mirrored
/// pairs (entry 2k + 1 the mirror of entry 2k) as sampleGoalPoses() gives them; poses off the
/// carpet are dropped. With the halfway line the draws are about the two poses it gives; without,
/// their headings are spread evenly over the circle.
std::vector<math::SE2> centreCirclePoses(const CentreCircleSighting& sighting,
                                         const world::FieldMap& map,
                                         const CentreCircleConfig& config, int count,
                                         math::Rng& rng);

}  // namespace adaptive_perception::localization
