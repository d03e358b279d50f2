#include "adaptive_perception/io/carmen_log.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

#include "../refusal.h"

using namespace adaptive_perception::io;
using adaptive_perception::test_support::refusedNaming;

namespace {
// `text` written to a file of the test's temporary folder; returns its path.
std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The message of the std::runtime_error that f() throws, or "accepted".
template <class F>
std::string failure(F&& f) {
  return adaptive_perception::test_support::refusal<std::runtime_error>(f);
}

// A FLASER line of `ranges` (written as given), the laser and robot at the origin.
std::string flaser(const std::vector<std::string>& ranges, double t, const char* name = "FLASER") {
  std::string line = std::string(name) + " " + std::to_string(ranges.size());
  for (const std::string& r : ranges) line += " " + r;
  return line + " 0 0 0 0 0 0 " + std::to_string(t) + " host 0.1\n";
}

bool isNoReturn(float r) { return std::isinf(r) && r > 0; }
}  // namespace

TEST(CarmenLog, ParsesEachMessageType) {
  const std::string text =
      "# CARMEN Logfile\n"
      "PARAM robot_front_laser_max 50.0 nohost 0\n"
      "FLASER 3 1.0 2.0 3.0 0.1 0.2 0.3 0.0 0.1 0.2 100.5 host 0.1\n"
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 100.6 host 0.2\n"
      "TRUEPOS 5.0 6.0 1.0 1.0 2.0 0.5 100.7 host 0.3\n"
      "ROBOTLASER1 0 -1.5 3.0 0.75 20.0 0.01 0 5 1 2 3 4 5 0 0.1 0.2 0.3 0.4 0.5 0.6 0.0 0.0 0.5 "
      "0.5 0.2 100.8 host 0.4\n"
      "SYNC foo\n";
  const CarmenLog log = parseCarmenLog(text);
  EXPECT_TRUE(log.issues.empty()) << log.issues.front().what;
  ASSERT_EQ(log.lasers.size(), 2u);
  const CarmenLaser& f = log.lasers[0];
  EXPECT_EQ(f.type, "FLASER");
  EXPECT_EQ(f.ranges_m.size(), 3u);
  EXPECT_NEAR(f.angle_min_rad, -M_PI / 2, 1e-12);
  EXPECT_NEAR(f.angle_increment_rad, M_PI / 2, 1e-12);  // 3 readings over 180 degrees
  EXPECT_DOUBLE_EQ(f.max_range_m, 50.0);                // from PARAM
  EXPECT_DOUBLE_EQ(f.timestamp_s, 100.5);
  EXPECT_DOUBLE_EQ(f.laser_pose.x_m, 0.1);
  EXPECT_DOUBLE_EQ(f.robot_pose.y_m, 0.1);
  const CarmenLaser& r = log.lasers[1];
  EXPECT_EQ(r.type, "ROBOTLASER1");
  EXPECT_EQ(r.ranges_m.size(), 5u);
  EXPECT_DOUBLE_EQ(r.angle_min_rad, -1.5);
  EXPECT_DOUBLE_EQ(r.angle_increment_rad, 0.75);
  EXPECT_DOUBLE_EQ(r.max_range_m, 20.0);
  EXPECT_DOUBLE_EQ(r.laser_pose.x_m, 0.1);
  EXPECT_DOUBLE_EQ(r.robot_pose.x_m, 0.4);
  EXPECT_DOUBLE_EQ(r.timestamp_s, 100.8);
  ASSERT_EQ(log.odometry.size(), 1u);
  EXPECT_DOUBLE_EQ(log.odometry[0].pose.yaw_rad, 0.5);
  EXPECT_DOUBLE_EQ(log.odometry[0].tv_mps, 0.3);
  ASSERT_EQ(log.true_poses.size(), 1u);
  EXPECT_DOUBLE_EQ(log.true_poses[0].true_pose.x_m, 5.0);
  EXPECT_EQ(log.comments, 1);
}

TEST(CarmenLog, ReadingsAtTheMaximumRangeAreNoReturns) {
  // Intel's log has no PARAM: the 81.9 m default, and its laser writes 81.83 for no return.
  const std::string text =
      "FLASER 4 1.0 81.83 81.95 2.0 0 0 0 0 0 0 100.0 host 0.1\n"
      "PARAM robot_front_laser_max 50.0 nohost 0\n"
      "FLASER 3 49.89 49.91 3.0 0 0 0 0 0 0 100.1 host 0.2\n";
  const CarmenLog log = parseCarmenLog(text);
  ASSERT_EQ(log.lasers.size(), 2u);
  const auto& a = log.lasers[0].ranges_m;
  EXPECT_FLOAT_EQ(a[0], 1.0f);
  EXPECT_TRUE(std::isinf(a[1]) && a[1] > 0);  // 81.83 >= 81.9 - 0.1
  EXPECT_TRUE(std::isinf(a[2]) && a[2] > 0);  // beyond the maximum
  EXPECT_FLOAT_EQ(a[3], 2.0f);
  const auto& b = log.lasers[1].ranges_m;
  EXPECT_FLOAT_EQ(b[0], 49.89f);  // just short of 50 - 0.1: a wall
  EXPECT_TRUE(std::isinf(b[1]));
  EXPECT_EQ(log.no_returns, 3);
}

TEST(CarmenLog, ReportsBadLinesWithNumbersAndKeepsGoing) {
  const std::string text =
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 10.0 host 0.2\n"
      "FLASER 180 1.0 2.0\n"                          // 2: truncated
      "ODOM 1.0 two 0.5 0.3 0.1 0.0 11.0 host 0.2\n"  // 3: malformed number
      "WEIRDMSG 1 2 3\n"                              // 4: unknown
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 9.0 host 0.2\n"   // 5: out of order (kept)
      "FLASER -4 1 2\n"                               // 6: bad count
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 12.0 host 0.2\n"
      "ROBOTLASER1 0 -1.5 3.0 0.75 20.0 0.01 0 5 1 2\n"  // 8: truncated
      "ODOM 1.0 2.0 0.5";                                // 9: truncated last line
  CarmenLog log = parseCarmenLog(text);
  std::vector<long> lines;
  for (const auto& i : log.issues) lines.push_back(i.line);
  EXPECT_EQ(lines, (std::vector<long>{2, 3, 4, 5, 6, 8, 9}));
  EXPECT_EQ(log.unknown, 1);
  EXPECT_EQ(log.out_of_order, 1);
  ASSERT_EQ(log.odometry.size(), 3u);
  log.sortByTime();
  EXPECT_DOUBLE_EQ(log.odometry[0].timestamp_s, 9.0);
  EXPECT_DOUBLE_EQ(log.odometry[2].timestamp_s, 12.0);
}

TEST(CarmenLog, RefusesCountsTooLargeForTheLine) {
  // A remission count of 1e44 (found by fuzz_carmen_log: its cast to size_t was undefined).
  const std::string text =
      "ROBOTLASER1 0 -1.5 3.0 0.75 20.0 0.01 0 5 1 2 3 4 5 1e44 0.1 0.2 0.3 0.4 0.5 0.6 0.0 0.0 0.5 "
      "0.5 0.2 100.8 host 0.4\n"
      "ROBOTLASER1 0 -1.5 3.0 0.75 20.0 0.01 0 5 1 2 3 4 5 1e300 0.1 0.2 0.3 0.4 0.5 0.6 0.0 0.0 "
      "0.5 0.5 0.2 100.9 host 0.4\n";
  const CarmenLog log = parseCarmenLog(text);
  ASSERT_EQ(log.issues.size(), 2u);
  EXPECT_EQ(log.issues[0].line, 1);
  EXPECT_NE(log.issues[0].what.find("remission count"), std::string::npos) << log.issues[0].what;
  EXPECT_TRUE(log.lasers.empty());
}

TEST(CarmenLog, ReadsBzip2AndFailsClearlyOnMissingFile) {
  EXPECT_THROW(readCarmenLog("/nonexistent/log.clf"), std::runtime_error);
  const std::string path = ::testing::TempDir() + "/notbz.clf.bz2";
  std::ofstream(path) << "this is not bzip2";
  try {
    readCarmenLog(path);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
  }
  // The project's bundled real log (copied with its licence) reads directly from .bz2.
  const CarmenLog log = readCarmenLog(std::string(AP_SOURCE_DIR) + "/data/laser/mit-csail.clf.bz2");
  EXPECT_EQ(log.lasers.size(), 1988u);
  EXPECT_TRUE(log.issues.empty());
  EXPECT_EQ(log.lasers[0].ranges_m.size(), 361u);
}

TEST(CarmenLog, TellsWhetherTheLasersPosesMove) {
  // FLASER n ranges.. laser_x laser_y laser_th robot_x robot_y robot_th ipc_timestamp host logger
  const std::string still =
      "FLASER 2 1.0 2.0 0 0 0 0 0 0 100.0 host 0.1\n"
      "FLASER 2 1.0 2.0 0 0 0 0 0 0 100.2 host 0.3\n"
      "ODOM 0.5 0.0 0.0 0.3 0.0 0.0 100.1 host 0.2\n";
  EXPECT_FALSE(laserPosesMove(parseCarmenLog(still)));
  const std::string moving =
      "FLASER 2 1.0 2.0 0 0 0 0 0 0 100.0 host 0.1\n"
      "FLASER 2 1.0 2.0 0 0 0 0 0 0.01 100.2 host 0.3\n";
  EXPECT_TRUE(laserPosesMove(parseCarmenLog(moving)));
  EXPECT_FALSE(laserPosesMove(CarmenLog()));
}

TEST(CarmenLog, RefusesAParamMaximumRangeThatIsNoRange) {
  // 0 made every reading +inf (each is >= 0 - margin); a negative one too; nan, inf or a word were
  // ignored for the 81.9 m default. Each is refused naming the file, the line and the value.
  for (const std::string value : {"0", "-5", "0.0", "nan", "inf", "1e999", "far"}) {
    const std::string path = writeTemp("param_" + value + ".clf",
                                       "# log\n"
                                       "PARAM robot_front_laser_max " +
                                           value + " nohost 0\n" + flaser({"1.0", "2.0"}, 10.0));
    const std::string message = failure([&] { readCarmenLog(path); });
    EXPECT_NE(message.find(path + ":2:"), std::string::npos) << value << ": " << message;
    EXPECT_NE(message.find("'" + value + "'"), std::string::npos) << value << ": " << message;
  }
  const std::string rear = "PARAM robot_rear_laser_max -1 nohost 0\n";
  EXPECT_NE(failure([&] { parseCarmenLog(rear, {}, "rear.clf"); }).find("rear.clf:1:"),
            std::string::npos);
  // A PARAM that gives no value at all is no range either.
  EXPECT_NE(failure([&] { parseCarmenLog("PARAM robot_front_laser_max\n"); }).find("''"),
            std::string::npos);
  // Other PARAMs are not laser ranges; a positive one is taken.
  const CarmenLog ok = parseCarmenLog(
      "PARAM robot_front_laser_max 20 nohost 0\nPARAM navigator_max_laser_range 0 nohost 0\n" +
      flaser({"1.0", "19.95"}, 10.0));
  ASSERT_EQ(ok.lasers.size(), 1u);
  EXPECT_DOUBLE_EQ(ok.lasers[0].max_range_m, 20.0);
  EXPECT_EQ(ok.lasers[0].range_source, CarmenRangeSource::kParam);
  EXPECT_TRUE(isNoReturn(ok.lasers[0].ranges_m[1]));
  // With the maximum range given, the bad PARAM is only reported.
  CarmenReadOptions given;
  given.max_range_m = 30.0;
  const CarmenLog log =
      parseCarmenLog("PARAM robot_front_laser_max 0 nohost 0\n" + flaser({"1.0", "29.95"}, 10.0),
                     given);
  ASSERT_EQ(log.lasers.size(), 1u);
  EXPECT_DOUBLE_EQ(log.lasers[0].max_range_m, 30.0);
  EXPECT_FLOAT_EQ(log.lasers[0].ranges_m[0], 1.0f);
  EXPECT_TRUE(isNoReturn(log.lasers[0].ranges_m[1]));
  ASSERT_EQ(log.issues.size(), 1u);
  EXPECT_EQ(log.issues[0].line, 1);
}

TEST(CarmenLog, FindsTheNoReturnValueInALogWithoutParam) {
  // No PARAM, and a laser that writes 50.00 when nothing reflects (a few scans, 4 no returns each,
  // written 50.00 and 50.0): with the 81.9 m default they were walls at 50 m and no_returns = 0.
  std::string text;
  for (int i = 0; i < 5; ++i)
    text += flaser({"1.25", "50.00", "3.5", "50.0", "12.0", "50.00", "49.2", "50.00"}, 10.0 + i);
  text += flaser({"2.0", "50.00", "7.0"}, 20.0, "RLASER");  // the rear laser: its own readings
  const CarmenLog log = parseCarmenLog(text);
  ASSERT_EQ(log.lasers.size(), 6u);
  for (int i = 0; i < 5; ++i) {
    const CarmenLaser& l = log.lasers[i];
    EXPECT_DOUBLE_EQ(l.max_range_m, 50.0);
    EXPECT_EQ(l.range_source, CarmenRangeSource::kInferred);
    EXPECT_FLOAT_EQ(l.ranges_m[0], 1.25f);
    EXPECT_TRUE(isNoReturn(l.ranges_m[1]) && isNoReturn(l.ranges_m[3]) &&
                isNoReturn(l.ranges_m[5]) && isNoReturn(l.ranges_m[7]));
    EXPECT_FLOAT_EQ(l.ranges_m[6], 49.2f);  // a wall just short of the maximum
  }
  EXPECT_EQ(log.no_returns, 20);  // the rear laser's one 50.00 is too few to tell: not one
  const CarmenLaser& r = log.lasers[5];
  EXPECT_EQ(r.range_source, CarmenRangeSource::kDefault);
  EXPECT_DOUBLE_EQ(r.max_range_m, 81.9);
  EXPECT_FLOAT_EQ(r.ranges_m[1], 50.0f);
  // What was found, for carmen_to_bag's summary.
  ASSERT_EQ(log.max_ranges.size(), 2u);
  EXPECT_EQ(log.max_ranges[0].type, "FLASER");
  EXPECT_EQ(log.max_ranges[0].source, CarmenRangeSource::kInferred);
  EXPECT_EQ(log.max_ranges[0].lines, 5);
  EXPECT_EQ(log.max_ranges[0].readings_at_max, 20);
  EXPECT_EQ(maxRangeSummary(log), "FLASER:50m(inferred),RLASER:81.9m(default)");
  // Fewer than no_return_min_count readings at the largest value: not taken.
  CarmenReadOptions strict;
  strict.no_return_min_count = 21;
  EXPECT_EQ(parseCarmenLog(text, strict).no_returns, 0);
}

TEST(CarmenLog, AGenuineFarWallIsNotANoReturn) {
  // No PARAM; the largest reading, 42.5 m, is a real wall seen once.
  std::string text;
  for (int i = 0; i < 20; ++i) text += flaser({"1.0", "2.0", "3.0", "4.0"}, 10.0 + i);
  text += flaser({"1.0", "42.5", "3.0", "4.0"}, 40.0);
  CarmenLog log = parseCarmenLog(text);
  EXPECT_EQ(log.no_returns, 0);
  EXPECT_FLOAT_EQ(log.lasers.back().ranges_m[1], 42.5f);
  EXPECT_EQ(log.lasers.back().range_source, CarmenRangeSource::kDefault);
  EXPECT_EQ(maxRangeSummary(log), "FLASER:81.9m(default)");
  // A far wall seen in many scans comes back with noise: its largest value is exactly repeated
  // (12 times) but fewer times than the values just below it (36).
  text.clear();
  for (int i = 0; i < 12; ++i) text += flaser({"1.0", "30.02", "29.99", "30.00", "30.01"}, 50.0 + i);
  log = parseCarmenLog(text);
  EXPECT_EQ(log.no_returns, 0);
  EXPECT_FLOAT_EQ(log.lasers[0].ranges_m[1], 30.02f);
  // A log of nothing but zeros has no no-return value either.
  text.clear();
  for (int i = 0; i < 12; ++i) text += flaser({"0", "0"}, 70.0 + i);
  EXPECT_EQ(parseCarmenLog(text).no_returns, 0);
}

TEST(CarmenLog, TheGivenMaximumRangeOverridesTheLog) {
  std::string text = "PARAM robot_front_laser_max 80 nohost 0\n";
  for (int i = 0; i < 12; ++i) text += flaser({"1.0", "50.00", "39.95"}, 10.0 + i);
  text +=
      "ROBOTLASER1 0 -1.5 3.0 0.75 20.0 0.01 0 3 1 39.95 45 0 0.1 0.2 0.3 0.4 0.5 0.6 0.0 0.0 "
      "0.5 0.5 0.2 100.8 host 0.4\n";
  CarmenReadOptions options;
  options.max_range_m = 40.0;
  const CarmenLog log = parseCarmenLog(text, options);
  ASSERT_EQ(log.lasers.size(), 13u);
  for (const CarmenLaser& l : log.lasers) {
    EXPECT_DOUBLE_EQ(l.max_range_m, 40.0);
    EXPECT_EQ(l.range_source, CarmenRangeSource::kOption);
    EXPECT_FLOAT_EQ(l.ranges_m[0], 1.0f);
    EXPECT_TRUE(isNoReturn(l.ranges_m[1]) && isNoReturn(l.ranges_m[2]));
  }
  EXPECT_EQ(maxRangeSummary(log), "FLASER:40m(option),ROBOTLASER1:40m(option)");
}

TEST(CarmenLog, SkipsALineStampedOutsideTheTimestampRangeAndKeepsTheRest) {
  // A timestamp of 2^32 s or more (or a negative one) cannot be a 32-bit count of seconds:
  // carmen_to_bag's ros::Time threw on it and the whole conversion stopped.
  const std::string text =
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 10.0 host 0.2\n"
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 4294967296 host 0.2\n"  // 2: 2^32
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 11.0 host 0.2\n" +
      flaser({"1.0", "2.0"}, 1e10) +                          // 4
      "TRUEPOS 5.0 6.0 1.0 1.0 2.0 0.5 -3 host 0.3\n"        // 5
      "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 1e400 host 0.2\n" +      // 6: no number at all
      flaser({"1.0", "2.0"}, 12.0) + "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 4294967295 host 0.2\n";
  const CarmenLog log = parseCarmenLog(text);
  std::vector<long> lines;
  for (const auto& i : log.issues) lines.push_back(i.line);
  EXPECT_EQ(lines, (std::vector<long>{2, 4, 5, 6}));
  EXPECT_NE(log.issues[0].what.find("4294967296"), std::string::npos) << log.issues[0].what;
  EXPECT_NE(log.issues[0].what.find("skipped"), std::string::npos) << log.issues[0].what;
  EXPECT_EQ(log.bad_timestamps, 3);
  ASSERT_EQ(log.odometry.size(), 3u);  // 10, 11 and 2^32 - 1, the last representable second
  EXPECT_DOUBLE_EQ(log.odometry[2].timestamp_s, 4294967295.0);
  ASSERT_EQ(log.lasers.size(), 1u);
  EXPECT_EQ(log.lasers[0].line, 7);
  EXPECT_TRUE(log.true_poses.empty());
  EXPECT_EQ(log.out_of_order, 0);  // the skipped stamp is not the one later lines are held to
  // The range is an option.
  CarmenReadOptions narrow;
  narrow.min_timestamp_s = 10.5;
  narrow.max_timestamp_s = 100.0;
  EXPECT_EQ(parseCarmenLog(text, narrow).odometry.size(), 1u);
}

TEST(CarmenLog, RefusesABzip2ThatDecompressesBeyondTheLimit) {
  // Two concatenated bzip2 streams: 50000 ODOM lines (2,200,000 bytes of text from 419 bytes) and
  // one FLASER line (49 bytes), made with Python's bz2.compress.
  static const char kBz2[] =
    "\x42\x5a\x68\x39\x31\x41\x59\x26\x53\x59\x66\x4b\xa6\x78\x05\xee\x13\xdd\x80\x00\x10\x40\x01\x7a"
    "\x00\x04\x02\x80\x40\x8c\x00\x30\x01\x50\x00\xa6\x00\x00\x4d\x52\x49\x93\x08\x0a\x60\x00\x37\x8a"
    "\x01\x5b\xc5\x00\xae\x22\x80\x57\xe8\xa0\x15\xcc\x50\x0a\xe6\x28\x05\x77\x14\x02\xb2\x8a\x01\x59"
    "\x91\x40\x2b\x88\xa0\x15\x91\x40\x2b\x88\xa0\x15\x90\x10\x54\xea\xa2\x80\x57\x51\x40\x2b\x51\x40"
    "\x2b\x2a\x28\x05\x6d\x14\x02\xb6\x8a\x01\x5a\xa2\x80\x56\x45\x00\xac\x8a\x01\x59\x45\x00\xaf\x21"
    "\x40\x2b\x5d\xc5\x00\xaf\x05\x00\xad\x45\x00\xaf\x91\x40\x2b\xec\x50\x0a\xfd\x14\x02\xbf\x98\xa0"
    "\xac\x93\x29\xac\x98\x5f\x30\x24\x82\x57\x3d\xee\xc0\x00\x08\x20\x00\xbd\x00\x02\x01\x40\x20\x46"
    "\x00\x18\x00\x9c\x00\x53\x00\x00\x53\x00\x00\x26\xaa\x4d\x1a\x98\x46\x9c\x45\x00\xae\x22\x80\x56"
    "\xa2\x80\x57\xb1\x40\x2b\x98\xa0\x15\xcc\x50\x0a\xee\x28\x05\x60\xa2\x04\x6a\x28\x05\x62\x28\x05"
    "\x68\x50\x0a\xc4\x04\x15\x3a\x51\x40\x2b\xa8\xa0\x15\xb4\x50\x0a\xc5\x45\x00\xac\xc5\x00\xac\xc5"
    "\x00\xad\xf3\x45\x00\xad\xa2\x80\x56\x05\x00\xac\x51\x40\x2b\xca\x28\x05\x77\x14\x02\xbc\x8a\x01"
    "\x5b\xc5\x00\xaf\xb1\x40\x2b\xf4\x50\x0a\xf6\x28\x05\x7f\x31\x41\x59\x26\x53\x59\xa4\x0e\x05\x1b"
    "\x00\xc3\x54\xdd\x80\x00\x10\x40\x01\x7a\x00\x04\x02\x80\x40\x8c\x00\x30\x01\x38\x00\xa6\x00\x00"
    "\xa6\x00\x00\x29\x51\x27\xa0\x9a\x64\xd1\x05\x43\x44\x15\x0d\xc8\x2a\x1e\x90\x54\x39\x20\xa8\x72"
    "\x41\x50\xfb\x40\xa8\x62\x90\x92\x5b\xd0\x2a\x1c\x64\x82\xa1\xc5\x02\xa1\x82\x45\x0a\x75\x54\x0a"
    "\x87\x44\x15\x0c\x90\x54\x30\x10\x54\x36\x20\xa8\x6c\x41\x50\xcd\x40\xa8\x60\x82\xa1\x8a\x05\x43"
    "\x02\x0a\x87\x6a\x05\x43\x54\x0a\x87\x74\x0a\x87\xc2\x0a\x87\xe2\x0a\x87\x84\x15\x0f\x48\x2a\x1f"
    "\xc5\xdc\x91\x4e\x14\x24\x17\x17\x17\x1a\x00\x42\x5a\x68\x39\x31\x41\x59\x26\x53\x59\xb0\xf1\xde"
    "\x76\x00\x00\x14\xdf\x80\x00\x10\x40\x01\x7a\x00\x23\x04\x18\x00\x00\x40\x8c\x00\x20\x00\x31\x4d"
    "\x32\x31\x31\x31\x06\x9a\x4d\x0d\x06\x40\xcc\x13\xd7\x51\x04\x39\xa8\x2e\xe1\x0a\x61\x5a\x8a\xc4"
    "\x08\x9d\x4c\xcd\xb9\xdf\x7c\x5d\xc9\x14\xe1\x42\x42\xc3\xc7\x79\xd8";
  const std::string path = writeTemp("bomb.clf.bz2", std::string(kBz2, sizeof(kBz2) - 1));
  const std::uint64_t text_bytes = 2200000 + 49;
  CarmenReadOptions options;
  options.max_decompressed_bytes = text_bytes;  // exactly the text: read
  const CarmenLog log = readCarmenLog(path, options);
  EXPECT_EQ(log.odometry.size(), 50000u);
  EXPECT_EQ(log.lasers.size(), 1u);
  options.max_decompressed_bytes = text_bytes - 1;  // one byte short, in the second stream
  std::string message = failure([&] { readCarmenLog(path, options); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("max_decompressed_bytes"), std::string::npos) << message;
  options.max_decompressed_bytes = 1 << 20;  // in the middle of the first
  message = failure([&] { readCarmenLog(path, options); });
  EXPECT_NE(message.find(path + ": decompresses to more than 1048576 bytes"), std::string::npos)
      << message;
  // A cut archive keeps what it decompressed, as before.
  const std::string cut = writeTemp("cut.clf.bz2", std::string(kBz2, 300));
  EXPECT_GT(readCarmenLog(cut).odometry.size(), 0u);
}

TEST(CarmenLog, RefusesOptionsOutOfRange) {
  auto with = [](auto set) {
    CarmenReadOptions o;
    set(o);
    return [o] { parseCarmenLog("", o); };
  };
  EXPECT_TRUE(refusedNaming(with([](CarmenReadOptions& o) { o.max_range_m = -1; }), "max_range_m"));
  EXPECT_TRUE(refusedNaming(with([](CarmenReadOptions& o) { o.default_max_range_m = 0; }),
                            "default_max_range_m"));
  EXPECT_TRUE(refusedNaming(with([](CarmenReadOptions& o) { o.no_return_margin_m = NAN; }),
                            "no_return_margin_m"));
  EXPECT_TRUE(refusedNaming(with([](CarmenReadOptions& o) { o.no_return_min_count = 0; }),
                            "no_return_min_count"));
  EXPECT_TRUE(refusedNaming(with([](CarmenReadOptions& o) { o.min_timestamp_s = 5e9; }),
                            "min_timestamp_s"));
  EXPECT_TRUE(refusedNaming(with([](CarmenReadOptions& o) { o.max_decompressed_bytes = 0; }),
                            "max_decompressed_bytes"));
}
