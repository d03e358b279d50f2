#pragma once
// Reader for CARMEN log files (.clf, or .clf.bz2 read directly): FLASER, RLASER, ROBOTLASER1, ODOM
// and TRUEPOS messages. One message per line, `NAME fields... ipc_timestamp ipc_hostname
// logger_timestamp`. Malformed, truncated and unknown lines are skipped, counted and reported with
// their line numbers. Out-of-order lines (an ipc_timestamp earlier than the latest one of the same
// message type; the Intel log has ~10% of them, single messages stamped late) are kept and
// reported: sortByTime() puts them in place. A line whose ipc_timestamp lies outside
// [min_timestamp_s, max_timestamp_s] is skipped, counted in `bad_timestamps` and reported with its
// line: one bad line never costs the rest of the log. Reading fails (std::runtime_error naming the
// file, and the line where there is one) only on a file that cannot be opened or decompressed, one
// that decompresses to more than `max_decompressed_bytes`, and a PARAM laser maximum range that is
// no range (below).
//
// Old-style lasers (FLASER front, RLASER rear) carry no geometry: they are taken as a 180-degree
// scan starting at -90 degrees (RLASER: +90), the n readings spread evenly over it (increment pi /
// (n - 1) for an odd n such as 181 or 361, pi / n for an even n such as 180 or 360, which then
// stops one step short of +90). Their maximum range, the first of:
//   1. `max_range_m` of the options when it is set (> 0): the user's word, over everything the log
//      says (it also replaces ROBOTLASER1's own field);
//   2. the log's PARAM robot_front_laser_max / robot_rear_laser_max, for the lines after it. A
//      value that is not a positive finite number (0, -1, nan, inf, a word) is refused, naming the
//      file, line and value: 0 would make every reading a no return, inf none. With option 1 set it
//      is only reported as an issue;
//   3. found in the readings (no-return inference, below), over all the lines of that laser that
//      neither 1 nor 2 covers;
//   4. else `default_max_range_m`, a SICK LMS's 81.9 m.
// CarmenLog::max_ranges says which one each laser's lines took.
//
// No-return inference. A laser writes one fixed value when nothing reflects (a SICK LMS 81.83 m or
// 81.91 m, other loggers 50.0 m), and over a log it writes it many times; a real surface comes back
// with range noise, so its returns spread over the values below its farthest one, and the largest
// value alone is rare. So the largest finite reading m of the laser's uncovered lines is taken for
// its no-return value, and its maximum range, when all of
//   - m > 0,
//   - at least `no_return_min_count` readings are exactly m (the same number as the log writes it),
//   - more readings are exactly m than lie in the metre below it (laser::NoReturnConfig::gap_m);
// a far wall seen once, or a few times among its noisy neighbours, is not. (The bundled logs: intel
// 68313 readings at 81.83 and none in the metre below; mit-csail 23711 at 81.91, none below.)
//
// A reading within `no_return_margin_m` of the laser's maximum range (or beyond it) is the laser's
// "no return": it is stored as +inf, as REP 117 has it, and counted in `no_returns`, so that no
// consumer takes it for a wall.
#include <cstdint>
#include <string>
#include <vector>

#include "adaptive_perception/laser/no_return.h"

#include "adaptive_perception/math/se2.h"

namespace adaptive_perception::io {

/// Where a laser line's maximum range came from (the order above; kMessage: ROBOTLASER1's field).
enum class CarmenRangeSource { kOption, kParam, kMessage, kInferred, kDefault };
/// "option", "PARAM", "message", "inferred", "default".
const char* rangeSourceName(CarmenRangeSource source);

struct CarmenLaser {
  std::string type;          // FLASER | RLASER | ROBOTLASER1
  double timestamp_s = 0.0;  // ipc_timestamp
  double angle_min_rad = 0.0, angle_increment_rad = 0.0, max_range_m = 0.0;
  CarmenRangeSource range_source = CarmenRangeSource::kDefault;  // where max_range_m came from
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

/// One maximum range the lasers of one type took: by type, source and value, in the order of
/// their first line.
struct CarmenMaxRange {
  std::string type;  // FLASER | RLASER | ROBOTLASER1
  CarmenRangeSource source = CarmenRangeSource::kDefault;
  double max_range_m = 0.0;
  long lines = 0;            // laser lines that took it
  long readings_at_max = 0;  // kInferred: readings exactly at max_range_m
};

struct CarmenLog {
  std::vector<CarmenLaser> lasers;
  std::vector<CarmenOdom> odometry;
  std::vector<CarmenTruePos> true_poses;
  std::vector<CarmenIssue> issues;  // malformed / truncated / out-of-order lines, with line numbers
  long lines = 0, comments = 0, unknown = 0, skipped_known = 0;  // skipped_known: PARAM, SYNC, ...
  long out_of_order = 0;
  long bad_timestamps = 0;  // lines skipped for a timestamp outside the options' range
  long no_returns = 0;      // readings at the maximum range, stored as +inf
  std::vector<CarmenMaxRange> max_ranges;

  /// Stable sort of every message list by timestamp.
  void sortByTime();
};

/// The maximum ranges in one word, for a summary line: `FLASER:81.83m(inferred)`, several joined by
/// commas (`-` when there is no laser).
std::string maxRangeSummary(const CarmenLog& log);

struct CarmenReadOptions {
  double max_range_m = 0.0;           // > 0: every laser's maximum range (1. above); 0: the log's
  double default_max_range_m = 81.9;  // SICK LMS maximum when neither PARAM nor inference gives one
  // readings >= max - this are no returns, >= 0
  double no_return_margin_m = laser::NoReturnConfig{}.margin_m;
  // readings exactly at the largest value to take it, >= 1
  long no_return_min_count = laser::NoReturnConfig{}.min_count;
  // ipc_timestamps outside this are refused line by line. The default is what a 32-bit count of
  // seconds holds (Unix time to 2106, and ros::Time's range, which carmen_to_bag writes): CARMEN
  // stamps are gettimeofday()'s seconds, so one beyond it, or negative, is a corrupt line.
  double min_timestamp_s = 0.0;
  double max_timestamp_s = 4294967295.0;  // 2^32 - 1
  // A .bz2 that decompresses to more is refused: the text is held in memory. 1 GiB is 60 times the
  // largest of the bundled logs (intel: 16 MB of text), and keeps a small file that expands without
  // end (a bzip2 bomb) from exhausting the memory.
  std::uint64_t max_decompressed_bytes = std::uint64_t{1} << 30;
  size_t max_issues_kept = 1000;  // later issues are counted, not stored
};

/// Whether the lasers' robot poses move over the log (some loggers leave them zero): when they do,
/// each scan carries the odometry of its own instant, which carmen_to_bag prefers to ODOM lines.
bool laserPosesMove(const CarmenLog& log);

/// Reads a log from a file (.bz2 decompressed on the fly). Throws std::runtime_error naming the
/// file (and line) when it cannot be opened or decompressed, decompresses to more than
/// options.max_decompressed_bytes, or has a PARAM laser maximum range that is no range; throws
/// std::invalid_argument naming the option when an option is out of its range.
CarmenLog readCarmenLog(const std::string& path,
                        const CarmenReadOptions& options = CarmenReadOptions());
/// Parses log text (what readCarmenLog does after decompression); `source` names the text in
/// errors, as `source:line: ...`.
CarmenLog parseCarmenLog(const std::string& text,
                         const CarmenReadOptions& options = CarmenReadOptions(),
                         const std::string& source = "CARMEN log");

}  // namespace adaptive_perception::io
