#pragma once
// Reader for CARMEN log files (.clf, or .clf.bz2 read directly): FLASER, RLASER, ROBOTLASER1, ODOM
// and TRUEPOS messages. One message per line, `NAME fields... ipc_timestamp ipc_hostname
// logger_timestamp`. Malformed, truncated and unknown lines are skipped, counted and reported with
// their line numbers. Out-of-order lines (an ipc_timestamp earlier than the latest one of the same
// message type; the Intel log has ~10% of them, single messages stamped late) are kept and
// reported: sortByTime() puts them in place. Reading never fails on content, only on a file that
// cannot be opened or decompressed.
//
// Old-style lasers (FLASER front, RLASER rear) carry no geometry: they are taken as a 180-degree
// scan starting at -90 degrees (RLASER: +90), the n readings spread evenly over it (increment pi /
// (n - 1) for an odd n such as 181 or 361, pi / n for an even n such as 180 or 360, which then
// stops one step short of +90), with the maximum range from the log's PARAM robot_front_laser_max /
// robot_rear_laser_max when present, else `default_max_range_m`.
//
// A reading within `no_return_margin_m` of the laser's maximum range (or beyond it) is the laser's
// "no return" (a SICK LMS writes 81.83 m, or 81.91 m, when nothing reflects): it is stored as +inf,
// as REP 117 has it, and counted in `no_returns`, so that no consumer takes it for a wall.
#include <string>
#include <vector>

#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::io {

struct CarmenLaser {
  std::string type;          // FLASER | RLASER | ROBOTLASER1
  double timestamp_s = 0.0;  // ipc_timestamp
  double angle_min_rad = 0.0, angle_increment_rad = 0.0, max_range_m = 0.0;
  std::vector<float> ranges_m;
  math::SE2 laser_pose;  // laser in the odometry frame
  math::SE2 robot_pose;  // robot (odometry) in the odometry frame
  long line = 0;
};

struct CarmenOdom {
  double timestamp_s = 0.0;
  math::SE2 pose;
  double tv_mps = 0.0, rv_radps = 0.0;
  long line = 0;
};

struct CarmenTruePos {
  double timestamp_s = 0.0;
  math::SE2 true_pose, odom_pose;
  long line = 0;
};

struct CarmenIssue {
  long line;
  std::string what;
};

struct CarmenLog {
  std::vector<CarmenLaser> lasers;
  std::vector<CarmenOdom> odometry;
  std::vector<CarmenTruePos> true_poses;
  std::vector<CarmenIssue> issues;  // malformed / truncated / out-of-order lines, with line numbers
  long lines = 0, comments = 0, unknown = 0, skipped_known = 0;  // skipped_known: PARAM, SYNC, ...
  long out_of_order = 0;
  long no_returns = 0;  // readings at the maximum range, stored as +inf

  /// Stable sort of every message list by timestamp.
  void sortByTime();
};

struct CarmenReadOptions {
  double default_max_range_m = 81.9;  // SICK LMS maximum when the log has no PARAM
  double no_return_margin_m = 0.1;    // readings >= max - this are no returns, >= 0
  size_t max_issues_kept = 1000;      // later issues are counted, not stored
};

/// Whether the lasers' robot poses move over the log (some loggers leave them zero): when they do,
/// each scan carries the odometry of its own instant, which carmen_to_bag prefers to ODOM lines.
bool laserPosesMove(const CarmenLog& log);

/// Reads a log from a file (.bz2 decompressed on the fly). Throws std::runtime_error naming the
/// file when it cannot be opened or decompressed.
CarmenLog readCarmenLog(const std::string& path,
                        const CarmenReadOptions& options = CarmenReadOptions());
/// Parses log text (what readCarmenLog does after decompression).
CarmenLog parseCarmenLog(const std::string& text,
                         const CarmenReadOptions& options = CarmenReadOptions());

}  // namespace adaptive_perception::io
