// Whole CARMEN logs: counts of every line kind, file order kept when stamps step back, bad lines
// skipped and the first one named, and the same log read from a plain and from a gzipped file.
#include "simulator/robot_log/carmen_log.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <fstream>
#include <string>

#include "temp_dir.hpp"

namespace slam::robot_log {
namespace {

using ::testing::HasSubstr;

constexpr std::string_view kLog =
    "# CARMEN log\n"
    "PARAM robot_frontlaser_offset 0.04 host 0.5\n"
    "ODOM 0 0 0 0 0 0 0.9 host 0.9\n"
    "FLASER 3 1 2 81.91 0.04 0 0 0 0 0 1.0 host 1.0\n"
    "ODOM 0.1 0 0 0.1 0 0 1.05 host 1.05\n"
    "FLASER 3 1 2 3 0.14 0 0 0.1 0 0 1.1 host 1.1\n"
    "FLASER 3 1 2 3 0.14 0 0 0.1 0 0 1.08 host 1.08\n"  // stamp steps back
    "FLASER 3 1 2 0.1 0 0 0 0 0 1.2 host 1.2\n"         // one field short
    "RLASER 2 4 5 0 0 0 0.2 0 0 1.3 host 1.3\n"
    "ROBOTLASER1 0 -1 2 1 50 0.01 0 3 1 2 3 0 0.2 0 0 0.2 0 0 0 0 0 0 0 1.4 host 1.4\n"
    "SONAR 1 2 3\n"
    "\n"
    "FLASER 2 1 2 0 0 0 nan 0 0 1.5 host 1.5\r\n"  // no usable odometry pose
    "ODOM 0.3 0 0 0 0 0 1.6 host 1.6";             // no newline at the end

void expect_log(const RobotLog& log) {
  const LogStats& s = log.stats;
  EXPECT_EQ(s.lines, 14);
  EXPECT_EQ(s.scans, 5);
  EXPECT_EQ(s.odometry, 3);
  EXPECT_EQ(s.comments, 2);
  EXPECT_EQ(s.unknown_kinds, 1);
  EXPECT_EQ(s.bad_lines, 2);
  EXPECT_EQ(s.stamps_back, 1);
  EXPECT_EQ(s.stamp_jumps, 0);
  EXPECT_EQ(s.error_readings, 0);
  EXPECT_EQ(s.far_readings, 1);  // 81.91
  EXPECT_THAT(s.first_bad, HasSubstr("line 8: FLASER"));
  ASSERT_EQ(log.scans.size(), 5u);
  EXPECT_DOUBLE_EQ(log.scans[1].stamp_s, 1.1);
  EXPECT_DOUBLE_EQ(log.scans[2].stamp_s, 1.08);  // file order
  EXPECT_DOUBLE_EQ(log.scans[0].laser_in_robot.x, 0.04);
  EXPECT_DOUBLE_EQ(log.scans[3].laser_in_robot.theta, std::numbers::pi);  // RLASER
  EXPECT_DOUBLE_EQ(log.scans[4].max_range_m, 50.0);                       // ROBOTLASER1
  EXPECT_DOUBLE_EQ(log.scans[4].stamp_s, 1.4);
}

TEST(CarmenLog, CountsEveryKind) {
  expect_log(parse_carmen_text(kLog));
}

TEST(CarmenLog, ReadingsAndStampsThatSayNothingAreCountedNotFatal) {
  const RobotLog log = parse_carmen_text(
      "FLASER 4 1 2 3 4 0 0 0 0 0 0 100 host 100\n"
      "FLASER 4 nan -1 0 90 0 0 0 0.1 0 0 100.1 host 100.1\n"     // error readings; 90 m: beyond 81
      "FLASER 4 1 inf 2 -inf 0 0 0 0.2 0 0 100.05 host 100.05\n"  // stamp back 0.05 s
      "FLASER 4 1 2 3 4 0 0 0 0.3 0 0 10900 host 10900\n"         // three hours later
      "FLASER 4 1 2 3 4 0 0 0 0.4 0 0 3700 host 3700\n"           // two hours back
      "FLASER 4 1 2 3 4 nan 0 0 0.5 0 0 3700.1 host 3700.1\n"     // no laser pose
      "FLASER 4 1 2 3 4 0 0 0 3800 host 3800\n");                 // no odometry pose
  const LogStats& s = log.stats;
  EXPECT_EQ(s.scans, 5);
  EXPECT_EQ(s.bad_lines, 2);
  EXPECT_THAT(s.first_bad, HasSubstr("line 6: FLASER: pose or stamp field 0"));
  EXPECT_EQ(s.error_readings, 4);  // nan, -1, 0, -inf
  EXPECT_EQ(s.far_readings, 2);    // 90, inf
  EXPECT_EQ(s.stamps_back, 2);
  EXPECT_EQ(s.stamp_jumps, 2);
  ASSERT_EQ(log.scans.size(), 5u);
  const LaserScan& bad = log.scans[1];
  EXPECT_FALSE(bad.is_return(0) || bad.is_return(1) || bad.is_return(2) || bad.is_return(3));
  EXPECT_TRUE(log.scans[2].is_return(0) && log.scans[2].is_return(2));
  EXPECT_DOUBLE_EQ(log.scans[4].stamp_s, 3700);  // file order kept
}

TEST(CarmenLog, PlainAndGzipFilesReadAlike) {
  const testkit::TempDir dir("carmen-log");
  const auto plain = dir / "robot.clf";
  std::ofstream(plain) << kLog;
  const auto packed = dir / "robot.clf.gz";
  gzFile gz = gzopen(packed.c_str(), "wb");
  ASSERT_NE(gz, nullptr);
  ASSERT_EQ(gzwrite(gz, kLog.data(), static_cast<unsigned>(kLog.size())), static_cast<int>(kLog.size()));
  ASSERT_EQ(gzclose(gz), Z_OK);
  // Magic, not the name, decides: a gzip file without ".gz" reads the same.
  const auto renamed = dir / "robot.log";
  std::filesystem::copy_file(packed, renamed);

  for (const auto& path : {plain, packed, renamed}) {
    auto log = read_carmen_log(path);
    ASSERT_TRUE(log) << path << ": " << log.message();
    SCOPED_TRACE(path.string());
    expect_log(*log);
  }
}

TEST(CarmenLog, LongLinesAreReadWhole) {
  std::string line = "FLASER 20000";
  for (int i = 0; i < 20000; ++i) line += " 12.345";
  line += " 0 0 0 0 0 0 1 host 1\n";
  const testkit::TempDir dir("carmen-log");
  std::ofstream(dir / "long.clf") << line << line;
  auto log = read_carmen_log(dir / "long.clf");
  ASSERT_TRUE(log) << log.message();
  EXPECT_EQ(log->stats.bad_lines, 0);
  ASSERT_EQ(log->scans.size(), 2u);
  EXPECT_EQ(log->scans[1].ranges.size(), 20000u);
}

TEST(CarmenLog, MissingOrBrokenFilesAreErrors) {
  const testkit::TempDir dir("carmen-log");
  EXPECT_THAT(read_carmen_log(dir / "none.clf").message(), HasSubstr("cannot open"));
  // A gzip stream cut in the middle.
  const auto packed = dir / "cut.clf.gz";
  gzFile gz = gzopen(packed.c_str(), "wb");
  std::string text;
  for (int i = 0; i < 2000; ++i) text += "ODOM 0 0 0 0 0 0 " + std::to_string(i) + " host 1\n";
  ASSERT_GT(gzwrite(gz, text.data(), static_cast<unsigned>(text.size())), 0);
  gzclose(gz);
  std::filesystem::resize_file(packed, std::filesystem::file_size(packed) / 2);
  EXPECT_THAT(read_carmen_log(packed).message(), HasSubstr("reading stopped"));
  CarmenOptions bad;
  bad.flaser_max_range_m = -1;
  EXPECT_FALSE(read_carmen_log(dir / "none.clf", bad));
}

}  // namespace
}  // namespace slam::robot_log
