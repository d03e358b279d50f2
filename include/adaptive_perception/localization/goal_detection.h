#pragma once
// Goals seen in a camera image, and the robot poses they put the robot at: the proposals of the
// global search on a field whose goals are round posts with a crossbar (the SPL field), where the
// image likelihood alone, scored on a coarse grid, can prefer a wrong pose (docs/
// field_localization.md).
//
// Contract: detectGoals() looks for goals whose two posts and crossbar are all in the image, with
// the camera's pose on the robot known (the head chain; the robot's pose on the field is not
// needed). A post is a vertical run of white pixels standing on the ground (not cut by the
// image's side); a goal is two posts whose feet a body lean of at most max_pitch_offset_rad puts
// the goal's width apart, each as wide and at least as tall as a post standing there, joined by a
// white crossbar at the posts' height, with a mouth that is mostly not white (a frame). Fields
// whose goals are panels (goal_post_diameter_m 0) or not white have none: nothing is found.
// goalPoses() turns a sighting into the robot's pose for each of the field's goals (two on a
// point-symmetric field: which one the robot sees is for the mirror test, the landmarks, to
// decide); sampleGoalPoses() draws poses with the sighting's uncertainty: the posts' bearings
// (their columns) are sharp, their ranges (their feet's rows) are not, and a goal seen nearly
// head-on tells little about where along the circle through its posts (the points that see them the
// same angle apart) the robot stands; the image likelihood decides that.
//
// "White" is the goal's paint under this image's light: chroma near neutral and luma near the line
// paint's (the pose-free segmentation's colours). A post stands on the field: the pixels below its
// foot are the segmentation's field.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <vector>

#include "adaptive_perception/color/field_segmentation.h"
#include "adaptive_perception/config/fields.h"
#include "adaptive_perception/math/rng.h"
#include "adaptive_perception/math/se2.h"
#include "adaptive_perception/world/camera_model.h"
#include "adaptive_perception/world/field_map.h"

namespace adaptive_perception::localization {

struct GoalDetectionConfig {
  // A pixel is white when its chroma is at most white_max_chroma levels from neutral
  // (sqrt((U - 128)^2 + (V - 128)^2)) and its luma at least white_min_luma_share of the way from
  // the carpet's to the line paint's (the pose-free segmentation's): a grey wall behind the goal
  // is lighter than the carpet but darker than paint.
  double white_max_chroma = 30.0;
  double white_min_luma_share = 0.6;
  // A post: neighbouring columns' runs of white (at least min_post_height_px long, gaps of up to
  // two rows bridged) that end on the same row, its foot, min_post_width_px or more columns wide,
  // nearly every column at least post_min_aspect_share as tall against the width as the post is.
  int min_post_height_px = 20;
  int min_post_width_px = 3;
  double post_min_aspect_share = 0.5;
  // In a goal, under the camera pitch the goal gives: each post as wide, and at least as tall, as
  // a post standing at its foot, up to this factor (a run may go on above the post into a white
  // background).
  double post_size_tolerance = 1.4;
  // At least this share of the pixels 2-7 rows below a post's foot are the field's.
  double post_min_field_below_share = 0.5;
  // A goal: a camera pitch offset of at most max_pitch_offset_rad puts two posts' feet the goal's
  // width apart, and at least crossbar_min_white_share of the crossbar, where that camera sees
  // it, is white.
  double max_pitch_offset_rad = 0.15;
  double crossbar_min_white_share = 0.6;
  // A goal is a white frame: at most this share of its mouth (between the posts, from a quarter to
  // three quarters of the crossbar's height) may be white. Two window mullions against a bright
  // sky (a white "crossbar" anywhere between them) are not a goal; a goal before a white wall is
  // not seen as one either (the uniform part of the search's pool still holds its pose). A half:
  // the majority of the mouth must show what is behind the goal.
  double mouth_max_white_share = 0.5;
  // Uncertainty of a sighting for sampleGoalPoses(): each post's bearing (its column) by
  // goal_bearing_sd_rad, the ratio of the posts' ranges (their feet's rows) by goal_range_ratio_sd
  // (standard deviation of its log). The ranges themselves follow from the goal's width.
  double goal_range_ratio_sd = 0.1;
  double goal_bearing_sd_rad = 0.01;

  static const config::Fields<GoalDetectionConfig>& fields();
  void validate() const { fields().validate(*this); }
};

struct GoalPostSighting {
  double u_px = 0.0;       // the post's centre column
  double foot_v_px = 0.0;  // its bottom edge, where it stands (in rayThrough()'s rows)
  double width_px = 0.0;   // columns
  double height_px = 0.0;  // rows (nearly every column at least this tall)
  // Its axis on the ground (its near side at foot_v_px, moved away by the radius), base_link frame
  // (in a GoalSighting: under the lean that puts the two axes the goal's width apart).
  Eigen::Vector2d foot_m{0, 0};
};

struct GoalSighting {
  GoalPostSighting left, right;  // left and right in the image
  double crossbar_white_share = 0.0;
  // The body's lean beyond the head chain's pose (leanCamera(); positive: forward, the camera
  // looking down) that puts the feet the goal's width apart: a legged robot's stance tilts its
  // camera (on the NAO development points by -0.03 to 0.09 rad).
  double pitch_offset_rad = 0.0;
  double mouth_white_share = 0.0;  // of the mouth, below the crossbar
};

/// The goals in `yuv` (CV_8UC3, Y U V) whose posts and crossbar are all in view and that are seen
/// from the carpet (goalPoses() on it), best first, none sharing a post. `segmentation` is the
/// image's pose-free segmentation (its carpet colour and line pixels); `base_to_optical` the
/// camera's pose on the robot (base_link -> camera_optical_frame). std::invalid_argument for
/// another image type or size, or labels of another size.
std::vector<GoalSighting> detectGoals(const cv::Mat& yuv,
                                      const color::FieldSegmentation& segmentation,
                                      const world::PinholeCamera& camera,
                                      const Eigen::Isometry3d& base_to_optical,
                                      const world::FieldMap& map,
                                      const GoalDetectionConfig& config);

/// The camera pose (base_link -> camera_optical_frame) when the robot's body leans forward by
/// `pitch_rad` (negative: back) beyond what the head chain says: the camera turned about
/// base_link's y axis, so that at any head yaw the lean tilts it as the stance does, where it is
/// (where the body pivots is not known, and turned about base_link's origin on the ground the
/// camera moved 4.5 cm at 0.09 rad: the NAO development point punt5 then ended 1.4 m off along
/// the goal's arc for one seed in three). GoalSighting::pitch_offset_rad is such a lean.
Eigen::Isometry3d leanCamera(const Eigen::Isometry3d& base_to_optical, double pitch_rad);

/// The robot poses (map -> base_link) that put the sighting's left and right feet on the left and
/// right posts of each of the map's goals (as seen from the field): one pose per goal, the heading
/// from the feet's direction and the position from their midpoint. Empty for a field without
/// posts.
std::vector<math::SE2> goalPoses(const GoalSighting& sighting, const world::FieldMap& map);

/// At most `count` poses drawn from the sighting's uncertainty (the config's), in groups of one
/// pose per map goal from the same draw (on a point-symmetric field, entry 2k + 1 is the point
/// mirror of entry 2k, as in PoseSearch's pools); groups with a pose off the carpet are dropped.
/// Empty for a field without posts.
std::vector<math::SE2> sampleGoalPoses(const GoalSighting& sighting, const world::FieldMap& map,
                                       const GoalDetectionConfig& config, int count,
                                       math::Rng& rng);

}  // namespace adaptive_perception::localization
