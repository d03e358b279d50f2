#pragma once
// Lists of single camera images with the head's joint angles and, where known, the robot's true
// position and the torso's pitch from its inertial unit (HeadChain::leanRad()): CSV with the
// header `image,head_pitch_rad,head_yaw_rad,x_m,y_m,torso_pitch_rad`, where the last three columns
// are optional (the header stops after head_yaw_rad or y_m, or a line leaves them empty). Blank
// lines and lines starting with '#' are skipped; relative image paths are relative to the CSV's
// folder.
// Errors (std::runtime_error) name the file and line: another header, a missing column, a number
// that does not parse or is not finite, x_m given without y_m.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace adaptive_perception::io {

struct HeadImage {
  std::string path;  // resolved (absolute or relative to the working directory)
  double head_pitch_rad = 0.0;
  double head_yaw_rad = 0.0;
  std::optional<Eigen::Vector2d> truth_xy_m;  // the robot's position on the field, if given
  std::optional<double> torso_pitch_rad;      // the inertial unit's torso pitch, if given
  int line = 0;                               // in the CSV, for messages
};

std::vector<HeadImage> readHeadImageList(const std::string& csv_path);

}  // namespace adaptive_perception::io
