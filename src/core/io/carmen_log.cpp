#include "adaptive_perception/io/carmen_log.h"

#include <bzlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <vector>

namespace adaptive_perception::io {

namespace {
constexpr double kPi = 3.14159265358979323846;

// Every bzip2 stream of `in` (concatenated streams follow one another), read in chunks so that no
// size passes through libbz2's 32-bit counters; more than `max_bytes` of output is refused.
std::string decompressBzip2(std::istream& in, const std::string& path, std::uint64_t max_bytes) {
  std::string out;
  std::vector<char> in_buf(1 << 16), out_buf(1 << 20);
  bz_stream s{};
  if (BZ2_bzDecompressInit(&s, 0, 0) != BZ_OK)
    throw std::runtime_error(path + ": bzip2 init failed");
  struct End {
    bz_stream* s;
    ~End() { BZ2_bzDecompressEnd(s); }
  } end{&s};
  bool eof = false;
  auto refill = [&] {
    in.read(in_buf.data(), static_cast<std::streamsize>(in_buf.size()));
    if (in.bad()) throw std::runtime_error(path + ": read error");
    s.next_in = in_buf.data();
    s.avail_in = static_cast<unsigned>(in.gcount());  // <= 64 KiB
    eof = s.avail_in == 0;
  };
  s.next_in = in_buf.data();
  while (true) {
    if (s.avail_in == 0 && !eof) refill();
    s.next_out = out_buf.data();
    s.avail_out = static_cast<unsigned>(out_buf.size());
    const int rc = BZ2_bzDecompress(&s);
    const std::uint64_t produced = out_buf.size() - s.avail_out;
    if (produced > max_bytes - out.size())
      throw std::runtime_error(path + ": decompresses to more than " + std::to_string(max_bytes) +
                               " bytes, the limit (CarmenReadOptions::max_decompressed_bytes, "
                               "carmen_to_bag --max_decompressed_mib): refused");
    out.append(out_buf.data(), produced);
    if (rc == BZ_STREAM_END) {
      if (s.avail_in == 0 && !eof) refill();
      if (s.avail_in == 0) break;
      // Concatenated stream: restart on the rest of the input.
      char* next = s.next_in;
      const unsigned avail = s.avail_in;
      BZ2_bzDecompressEnd(&s);
      s = bz_stream{};
      if (BZ2_bzDecompressInit(&s, 0, 0) != BZ_OK)
        throw std::runtime_error(path + ": bzip2 init failed");
      s.next_in = next;
      s.avail_in = avail;
      continue;
    }
    if (rc != BZ_OK) {
      if (!out.empty())
        break;  // a truncated archive: keep what was decompressed (the reader reports the cut line)
      throw std::runtime_error(path + ": not a valid bzip2 file (error " + std::to_string(rc) +
                               ")");
    }
    if (eof && s.avail_in == 0 && s.avail_out != 0) break;  // input ended without a stream end
  }
  return out;
}

std::string readFile(const std::string& path, std::uint64_t max_decompressed_bytes) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error(path + ": cannot open log file");
  if (path.size() >= 4 && path.compare(path.size() - 4, 4, ".bz2") == 0)
    return decompressBzip2(f, path, max_decompressed_bytes);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

bool toDouble(const std::string& s, double* v) {
  char* end = nullptr;
  *v = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0' && std::isfinite(*v);
}

// A number as a message shows it: up to `digits` significant digits (7: a float's), no trailing
// zeros.
std::string number(double v, int digits = 10) {
  std::ostringstream ss;
  ss << std::setprecision(digits) << v;
  return ss.str();
}

void validate(const CarmenReadOptions& o) {
  auto check = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("CarmenReadOptions: " + what);
  };
  check(std::isfinite(o.max_range_m) && o.max_range_m >= 0.0,
        "max_range_m = " + number(o.max_range_m) + " (allowed: 0, from the log, or > 0)");
  check(std::isfinite(o.default_max_range_m) && o.default_max_range_m > 0.0,
        "default_max_range_m = " + number(o.default_max_range_m) + " (allowed: > 0)");
  check(std::isfinite(o.no_return_margin_m) && o.no_return_margin_m >= 0.0,
        "no_return_margin_m = " + number(o.no_return_margin_m) + " (allowed: >= 0)");
  check(o.no_return_min_count >= 1,
        "no_return_min_count = " + std::to_string(o.no_return_min_count) + " (allowed: >= 1)");
  check(!(o.min_timestamp_s > o.max_timestamp_s) && !std::isnan(o.min_timestamp_s) &&
            !std::isnan(o.max_timestamp_s),
        "min_timestamp_s = " + number(o.min_timestamp_s) + " above max_timestamp_s = " +
            number(o.max_timestamp_s));
  check(o.max_decompressed_bytes >= 1, "max_decompressed_bytes = 0 (allowed: >= 1)");
}

// The no-return value of lasers[i] for i in `which` (the rule in the header; laser/no_return.h
// applies it), or 0 when there is none; *count: the readings exactly at it.
float inferNoReturn(const std::vector<CarmenLaser>& lasers, const std::vector<size_t>& which,
                    long min_count, long* count) {
  laser::NoReturnConfig config;
  config.min_count = min_count;
  laser::NoReturnFinder finder(config);
  for (size_t i : which)
    finder.add(lasers[i].ranges_m, std::numeric_limits<double>::infinity());
  const std::optional<double> m = finder.value();
  if (!m) return 0.0f;
  *count = finder.readingsAtValue();
  return static_cast<float>(*m);
}
}  // namespace

const char* rangeSourceName(CarmenRangeSource source) {
  switch (source) {
    case CarmenRangeSource::kOption:
      return "option";
    case CarmenRangeSource::kParam:
      return "PARAM";
    case CarmenRangeSource::kMessage:
      return "message";
    case CarmenRangeSource::kInferred:
      return "inferred";
    case CarmenRangeSource::kDefault:
      break;
  }
  return "default";
}

std::string maxRangeSummary(const CarmenLog& log) {
  std::string out;
  for (const CarmenMaxRange& r : log.max_ranges)
    out += (out.empty() ? "" : ",") + r.type + ":" + number(r.max_range_m, 7) + "m(" +
           rangeSourceName(r.source) + ")";
  return out.empty() ? "-" : out;
}

void CarmenLog::sortByTime() {
  auto by_time = [](const auto& a, const auto& b) { return a.timestamp_s < b.timestamp_s; };
  std::stable_sort(lasers.begin(), lasers.end(), by_time);
  std::stable_sort(odometry.begin(), odometry.end(), by_time);
  std::stable_sort(true_poses.begin(), true_poses.end(), by_time);
}

CarmenLog readCarmenLog(const std::string& path, const CarmenReadOptions& options) {
  validate(options);
  return parseCarmenLog(readFile(path, options.max_decompressed_bytes), options, path);
}

CarmenLog parseCarmenLog(const std::string& text, const CarmenReadOptions& options,
                         const std::string& source) {
  validate(options);
  CarmenLog log;
  const bool given = options.max_range_m > 0.0;
  // The PARAM maximum ranges seen so far (0: none yet).
  double front_max = 0.0, rear_max = 0.0;
  // Old-style laser lines with neither option nor PARAM: their range is found after the last line.
  std::vector<size_t> uncovered_front, uncovered_rear;
  std::map<std::string, double> last_time;
  auto issue = [&](long line, const std::string& what) {
    if (log.issues.size() < options.max_issues_kept) log.issues.push_back({line, what});
  };
  std::istringstream in(text);
  std::string raw;
  long line_no = 0;
  std::vector<std::string> tok;
  while (std::getline(in, raw)) {
    ++line_no;
    ++log.lines;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    tok.clear();
    {
      std::istringstream ls(raw);
      std::string t;
      while (ls >> t) tok.push_back(t);
    }
    if (tok.empty()) continue;
    if (tok[0][0] == '#') {
      ++log.comments;
      continue;
    }
    const std::string& name = tok[0];
    // Numbers of a message: every token but the name and the trailing `ipc_hostname
    // logger_timestamp`.
    auto numbers = [&](size_t count, std::vector<double>* v) -> bool {
      v->clear();
      if (tok.size() < count + 1) return false;
      for (size_t i = 1; i <= count; ++i) {
        double x;
        if (!toDouble(tok[i], &x)) return false;
        v->push_back(x);
      }
      return true;
    };
    // Whether to keep a message stamped t: one outside the timestamp range is skipped and counted;
    // one out of order is kept and reported.
    auto keep = [&](double t) {
      if (!(t >= options.min_timestamp_s && t <= options.max_timestamp_s)) {
        ++log.bad_timestamps;
        issue(line_no, name + ": timestamp " + number(t) + " s outside [" +
                           number(options.min_timestamp_s) + ", " +
                           number(options.max_timestamp_s) + "] s: line skipped");
        return false;
      }
      auto it = last_time.find(name);
      if (it != last_time.end() && t < it->second) {
        ++log.out_of_order;
        issue(line_no, name + ": timestamp " + std::to_string(t) + " earlier than the previous " +
                           name + " (" + std::to_string(it->second) + "): kept, out of order");
        return true;
      }
      last_time[name] = t;
      return true;
    };
    std::vector<double> v;
    if (name == "PARAM") {
      if (tok.size() >= 2 &&
          (tok[1] == "robot_front_laser_max" || tok[1] == "robot_rear_laser_max")) {
        const std::string value = tok.size() >= 3 ? tok[2].substr(0, 40) : "";
        double x;
        if (!toDouble(value, &x) || !(x > 0.0)) {
          const std::string what = "PARAM " + tok[1] + " '" + value +
                                   "': a laser's maximum range is a positive finite number of "
                                   "metres";
          if (!given)
            throw std::runtime_error(source + ":" + std::to_string(line_no) + ": " + what +
                                     " (or give the maximum range: "
                                     "CarmenReadOptions::max_range_m, carmen_to_bag "
                                     "--max_range_m)");
          issue(line_no, what + ": ignored, the maximum range is given");
        } else {
          (tok[1] == "robot_front_laser_max" ? front_max : rear_max) = x;
        }
      }
      ++log.skipped_known;
    } else if (name == "FLASER" || name == "RLASER") {
      double nd;
      if (tok.size() < 2 || !toDouble(tok[1], &nd) || nd < 1 || nd > 100000 ||
          nd != std::floor(nd)) {
        issue(line_no, name + ": bad reading count");
        continue;
      }
      const size_t n = static_cast<size_t>(nd);
      // count, n ranges, 6 poses, ipc_timestamp (+ hostname, logger_timestamp)
      if (!numbers(1 + n + 6 + 1, &v) || tok.size() < 1 + 1 + n + 6 + 3) {
        issue(line_no, name + ": truncated or malformed (" + std::to_string(tok.size()) +
                           " fields for " + std::to_string(n) + " readings)");
        continue;
      }
      CarmenLaser l;
      l.type = name;
      l.line = line_no;
      l.angle_increment_rad =
          (n % 2 == 1 && n > 1) ? kPi / static_cast<double>(n - 1) : kPi / static_cast<double>(n);
      l.angle_min_rad = name == "FLASER" ? -kPi / 2 : kPi / 2;
      const double param_max = name == "FLASER" ? front_max : rear_max;
      if (given) {
        l.max_range_m = options.max_range_m;
        l.range_source = CarmenRangeSource::kOption;
      } else if (param_max > 0.0) {
        l.max_range_m = param_max;
        l.range_source = CarmenRangeSource::kParam;
      }
      for (size_t i = 0; i < n; ++i) l.ranges_m.push_back(static_cast<float>(v[1 + i]));
      l.laser_pose = math::SE2(v[1 + n], v[2 + n], v[3 + n]);
      l.robot_pose = math::SE2(v[4 + n], v[5 + n], v[6 + n]);
      l.timestamp_s = v[7 + n];
      if (!keep(l.timestamp_s)) continue;
      if (!given && !(param_max > 0.0))
        (name == "FLASER" ? uncovered_front : uncovered_rear).push_back(log.lasers.size());
      log.lasers.push_back(std::move(l));
    } else if (name == "ROBOTLASER1") {
      // type start_angle fov resolution max_range accuracy remission_mode num_readings ...
      double nd;
      if (tok.size() < 9 || !toDouble(tok[8], &nd) || nd < 1 || nd > 100000 ||
          nd != std::floor(nd)) {
        issue(line_no, "ROBOTLASER1: bad reading count");
        continue;
      }
      const size_t n = static_cast<size_t>(nd);
      double nrd;
      // Bounded before the cast (a larger count cannot fit the line anyway; casting 1e44 to
      // size_t is undefined: found by fuzz_carmen_log).
      if (tok.size() < 9 + n + 1 || !toDouble(tok[9 + n], &nrd) || nrd < 0 ||
          nrd > static_cast<double>(tok.size()) || nrd != std::floor(nrd)) {
        issue(line_no, "ROBOTLASER1: truncated or malformed remission count");
        continue;
      }
      const size_t nr = static_cast<size_t>(nrd);
      const size_t total =
          8 + n + 1 + nr + 6 + 5 + 1;  // ... poses(6) tv rv fwd side turn(5) ipc_timestamp
      if (!numbers(total, &v) || tok.size() < total + 3) {
        issue(line_no,
              "ROBOTLASER1: truncated or malformed (" + std::to_string(tok.size()) + " fields)");
        continue;
      }
      CarmenLaser l;
      l.type = name;
      l.line = line_no;
      l.angle_min_rad = v[1];
      l.angle_increment_rad = v[3];
      l.max_range_m = given ? options.max_range_m : v[4];
      l.range_source = given ? CarmenRangeSource::kOption : CarmenRangeSource::kMessage;
      for (size_t i = 0; i < n; ++i) l.ranges_m.push_back(static_cast<float>(v[8 + i]));
      const size_t p = 8 + n + 1 + nr;
      l.laser_pose = math::SE2(v[p], v[p + 1], v[p + 2]);
      l.robot_pose = math::SE2(v[p + 3], v[p + 4], v[p + 5]);
      l.timestamp_s = v[p + 11];
      if (!(l.angle_increment_rad > 0.0) || !(l.max_range_m > 0.0)) {
        issue(line_no, "ROBOTLASER1: non-positive resolution or maximum range");
        continue;
      }
      if (keep(l.timestamp_s)) log.lasers.push_back(std::move(l));
    } else if (name == "ODOM") {
      if (!numbers(7, &v) || tok.size() < 10) {
        issue(line_no, "ODOM: truncated or malformed");
        continue;
      }
      CarmenOdom o{v[6], math::SE2(v[0], v[1], v[2]), v[3], v[4], line_no};
      if (keep(o.timestamp_s)) log.odometry.push_back(o);
    } else if (name == "TRUEPOS") {
      if (!numbers(7, &v) || tok.size() < 10) {
        issue(line_no, "TRUEPOS: truncated or malformed");
        continue;
      }
      CarmenTruePos t{v[6], math::SE2(v[0], v[1], v[2]), math::SE2(v[3], v[4], v[5]), line_no};
      if (keep(t.timestamp_s)) log.true_poses.push_back(t);
    } else if (name == "SYNC" || name == "NMEAGGA" || name == "NMEARMC" || name == "SONAR" ||
               name == "BUMPER" || name == "SCANMARK" || name == "POSITIONLASER" ||
               name == "RAWLASER1" || name == "RAWLASER2" || name == "RAWLASER3" ||
               name == "RAWLASER4" || name == "ROBOTLASER2" || name == "GPSNMEA") {
      ++log.skipped_known;
    } else {
      ++log.unknown;
      issue(line_no, "unknown message '" + name.substr(0, 40) + "'");
    }
  }

  // The uncovered old-style lasers: the no-return value found in their readings, else the default.
  std::map<std::string, long> inferred_count;  // by laser type: readings exactly at the value
  for (const std::vector<size_t>* which : {&uncovered_front, &uncovered_rear}) {
    if (which->empty()) continue;
    long count = 0;
    const float m = inferNoReturn(log.lasers, *which, options.no_return_min_count, &count);
    if (m > 0.0f) inferred_count[log.lasers[which->front()].type] = count;
    for (size_t i : *which) {
      log.lasers[i].max_range_m = m > 0.0f ? m : options.default_max_range_m;
      log.lasers[i].range_source =
          m > 0.0f ? CarmenRangeSource::kInferred : CarmenRangeSource::kDefault;
    }
  }
  // A reading at the laser's maximum (within no_return_margin_m) is its "no return" value: +inf.
  std::map<std::tuple<std::string, CarmenRangeSource, double>, size_t> range_index;
  for (CarmenLaser& l : log.lasers) {
    const double at = l.max_range_m - options.no_return_margin_m;
    for (float& r : l.ranges_m)
      if (r >= at) {
        r = std::numeric_limits<float>::infinity();
        ++log.no_returns;
      }
    const auto key = std::make_tuple(l.type, l.range_source, l.max_range_m);
    auto found = range_index.find(key);
    if (found == range_index.end()) {
      found = range_index.emplace(key, log.max_ranges.size()).first;
      log.max_ranges.push_back({l.type, l.range_source, l.max_range_m, 0,
                                l.range_source == CarmenRangeSource::kInferred
                                    ? inferred_count[l.type]
                                    : 0});
    }
    ++log.max_ranges[found->second].lines;
  }
  return log;
}

bool laserPosesMove(const CarmenLog& log) {
  for (const auto& l : log.lasers) {
    const math::SE2 d = math::between(log.lasers.front().robot_pose, l.robot_pose);
    if (std::hypot(d.x_m, d.y_m) > 1e-6 || std::fabs(d.yaw_rad) > 1e-6) return true;
  }
  return false;
}

}  // namespace adaptive_perception::io
