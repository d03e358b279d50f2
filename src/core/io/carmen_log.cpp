#include "adaptive_perception/io/carmen_log.h"

#include <bzlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace adaptive_perception::io {

namespace {
constexpr double kPi = 3.14159265358979323846;

std::string readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error(path + ": cannot open log file");
  std::stringstream ss;
  ss << f.rdbuf();
  std::string raw = ss.str();
  if (path.size() < 4 || path.compare(path.size() - 4, 4, ".bz2") != 0) return raw;
  // Decompress every bzip2 stream in the file.
  std::string out;
  bz_stream s{};
  if (BZ2_bzDecompressInit(&s, 0, 0) != BZ_OK)
    throw std::runtime_error(path + ": bzip2 init failed");
  s.next_in = raw.data();
  s.avail_in = static_cast<unsigned>(raw.size());
  std::vector<char> buf(1 << 20);
  while (true) {
    s.next_out = buf.data();
    s.avail_out = static_cast<unsigned>(buf.size());
    const int rc = BZ2_bzDecompress(&s);
    out.append(buf.data(), buf.size() - s.avail_out);
    if (rc == BZ_STREAM_END) {
      if (s.avail_in == 0) break;
      // Concatenated stream: restart.
      char* next = s.next_in;
      unsigned avail = s.avail_in;
      BZ2_bzDecompressEnd(&s);
      s = bz_stream{};
      BZ2_bzDecompressInit(&s, 0, 0);
      s.next_in = next;
      s.avail_in = avail;
      continue;
    }
    if (rc != BZ_OK) {
      BZ2_bzDecompressEnd(&s);
      if (!out.empty())
        break;  // a truncated archive: keep what was decompressed (the reader reports the cut line)
      throw std::runtime_error(path + ": not a valid bzip2 file (error " + std::to_string(rc) +
                               ")");
    }
    if (s.avail_in == 0 && s.avail_out != 0) break;  // input ended without a stream end: truncated
  }
  BZ2_bzDecompressEnd(&s);
  return out;
}

bool toDouble(const std::string& s, double* v) {
  char* end = nullptr;
  *v = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0' && std::isfinite(*v);
}
}  // namespace

void CarmenLog::sortByTime() {
  auto by_time = [](const auto& a, const auto& b) { return a.timestamp_s < b.timestamp_s; };
  std::stable_sort(lasers.begin(), lasers.end(), by_time);
  std::stable_sort(odometry.begin(), odometry.end(), by_time);
  std::stable_sort(true_poses.begin(), true_poses.end(), by_time);
}

CarmenLog readCarmenLog(const std::string& path, const CarmenReadOptions& options) {
  return parseCarmenLog(readFile(path), options);
}

CarmenLog parseCarmenLog(const std::string& text, const CarmenReadOptions& options) {
  CarmenLog log;
  double front_max = options.default_max_range_m, rear_max = options.default_max_range_m;
  std::map<std::string, double> last_time;
  auto issue = [&](long line, const std::string& what) {
    if (log.issues.size() < options.max_issues_kept) log.issues.push_back({line, what});
  };
  // A reading at the laser's maximum (within no_return_margin_m) is its "no return" value: +inf.
  auto markNoReturns = [&](CarmenLaser* l) {
    const double at = l->max_range_m - options.no_return_margin_m;
    for (float& r : l->ranges_m)
      if (r >= at) {
        r = std::numeric_limits<float>::infinity();
        ++log.no_returns;
      }
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
    auto inOrder = [&](double t) {
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
      if (tok.size() >= 3) {
        double x;
        if (tok[1] == "robot_front_laser_max" && toDouble(tok[2], &x)) front_max = x;
        if (tok[1] == "robot_rear_laser_max" && toDouble(tok[2], &x)) rear_max = x;
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
      l.max_range_m = name == "FLASER" ? front_max : rear_max;
      for (size_t i = 0; i < n; ++i) l.ranges_m.push_back(static_cast<float>(v[1 + i]));
      markNoReturns(&l);
      l.laser_pose = math::SE2(v[1 + n], v[2 + n], v[3 + n]);
      l.robot_pose = math::SE2(v[4 + n], v[5 + n], v[6 + n]);
      l.timestamp_s = v[7 + n];
      if (inOrder(l.timestamp_s)) log.lasers.push_back(std::move(l));
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
      l.max_range_m = v[4];
      for (size_t i = 0; i < n; ++i) l.ranges_m.push_back(static_cast<float>(v[8 + i]));
      markNoReturns(&l);
      const size_t p = 8 + n + 1 + nr;
      l.laser_pose = math::SE2(v[p], v[p + 1], v[p + 2]);
      l.robot_pose = math::SE2(v[p + 3], v[p + 4], v[p + 5]);
      l.timestamp_s = v[p + 11];
      if (!(l.angle_increment_rad > 0.0) || !(l.max_range_m > 0.0)) {
        issue(line_no, "ROBOTLASER1: non-positive resolution or maximum range");
        continue;
      }
      if (inOrder(l.timestamp_s)) log.lasers.push_back(std::move(l));
    } else if (name == "ODOM") {
      if (!numbers(7, &v) || tok.size() < 10) {
        issue(line_no, "ODOM: truncated or malformed");
        continue;
      }
      CarmenOdom o{v[6], math::SE2(v[0], v[1], v[2]), v[3], v[4], line_no};
      if (inOrder(o.timestamp_s)) log.odometry.push_back(o);
    } else if (name == "TRUEPOS") {
      if (!numbers(7, &v) || tok.size() < 10) {
        issue(line_no, "TRUEPOS: truncated or malformed");
        continue;
      }
      CarmenTruePos t{v[6], math::SE2(v[0], v[1], v[2]), math::SE2(v[3], v[4], v[5]), line_no};
      if (inOrder(t.timestamp_s)) log.true_poses.push_back(t);
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
