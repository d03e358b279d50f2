#pragma once
// The line-landmark map as YAML (written by ekf_slam_mapper's save_map service and by tools):
//   variant: standard
//   robot_pose: [x_m, y_m, yaw_rad]
//   landmarks:            # in the state
//     - {id: 3, rho_m: .., alpha_rad: .., sightings: .., confirmed: true,
//        pieces: [[x0, y0, x1, y1], ...]}
//   fixed_landmarks:      # anchored (covariance 0) or retired (their marginal covariance)
//     - {id: .., rho_m: .., alpha_rad: .., anchor: true, covariance: [4 values], pieces: ...}
//   state_covariance: {dim: n, data: [n*n values, row-major]}   # pose then landmarks
#include <string>

#include "adaptive_perception/slam/line_ekf_slam.h"

namespace adaptive_perception::slam {

/// Reads a map written by writeLineMapYaml back as landmarks to localize against
/// (LineEkfSlam::addFixedLandmarks): the confirmed landmarks of the state, each with its marginal
/// covariance from state_covariance, and the fixed ones with theirs; tentative landmarks are left
/// out. Throws std::runtime_error "PATH:LINE: what" on a file that cannot be read, a missing or
/// malformed field, a covariance of the wrong size or not symmetric positive semi-definite.
std::vector<FixedLandmark> readLineMapYaml(const std::string& path);

/// Writes to a temporary file beside `path` and renames it over `path`, so a failed write never
/// leaves a truncated map. Throws std::runtime_error naming the file.
void writeLineMapYaml(const std::string& path, const LineEkfSlam& slam);

}  // namespace adaptive_perception::slam
