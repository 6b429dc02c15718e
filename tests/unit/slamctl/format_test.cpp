// slamctl's parsing of mode names and its human-readable lines.
#include "slamctl/format.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace slam::ctl {
namespace {

TEST(SlamctlFormat, GoalModesRoundTripByName) {
  for (const char* name : {"idle", "direct", "planned", "square", "explore", "home", "stop"}) {
    const auto mode = parse_goal_mode(name);
    ASSERT_TRUE(mode) << name;
    EXPECT_EQ(goal_mode_name(*mode), name);
  }
  EXPECT_FALSE(parse_goal_mode("fly"));
  EXPECT_FALSE(parse_goal_mode("PLANNED"));
}

TEST(SlamctlFormat, RobotLineShowsPoseAgeAndMode) {
  RobotState s;
  s.robot_id("r7");
  s.presence(PRESENCE_ONLINE);
  s.protocol(PROTOCOL_V1);
  s.pose().x(1.5);
  s.pose().y(-2.25);
  s.last_seen_ns(1'000'000'000);
  s.messages(12);
  RobotPath p;
  p.mode(GOAL_EXPLORE);
  p.status(GOAL_STATUS_ACTIVE);
  const std::string line = format_robot(s, nullptr, &p, 3'500'000'000);
  EXPECT_NE(line.find("r7"), std::string::npos);
  EXPECT_NE(line.find("online"), std::string::npos);
  EXPECT_NE(line.find("1.50"), std::string::npos);
  EXPECT_NE(line.find("-2.25"), std::string::npos);
  EXPECT_NE(line.find("2.5 s ago"), std::string::npos);
  EXPECT_NE(line.find("explore/active"), std::string::npos);
  EXPECT_NE(line.find("correction -"), std::string::npos) << line;
}

TEST(SlamctlFormat, RobotLineShowsTheCorrection) {
  RobotState s;
  s.robot_id("r7");
  PoseCorrection c;
  c.robot_id("r7");
  c.map_from_odom().x(1.0);
  c.map_from_odom().y(-2.0);
  c.map_from_odom().theta(-1.5707963267948966);
  c.version(4);
  c.keyframes(31);
  c.loop_closures(2);
  c.source(CORRECTION_LOOP);
  const std::string line = format_robot(s, &c, nullptr, 0);
  EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1) << line;
  EXPECT_NE(line.find("correction (1.00, -2.00, -90.0 deg) version 4 keyframes 31 loops 2 loop"),
            std::string::npos)
      << line;
}

TEST(SlamctlFormat, PathReplyListsStatusAndPoints) {
  PathReply r;
  r.status(PLAN_GOAL_BLOCKED);
  r.reason("goal inside an obstacle");
  Point2 a;
  a.x(1);
  a.y(2);
  r.path().push_back(a);
  const std::string text = format_path_reply(r);
  EXPECT_NE(text.find("GOAL_BLOCKED"), std::string::npos);
  EXPECT_NE(text.find("goal inside an obstacle"), std::string::npos);
  EXPECT_NE(text.find("(1.00, 2.00)"), std::string::npos);
}

TEST(SlamctlFormat, HeartbeatListsCounters) {
  Heartbeat hb;
  hb.service("mapper");
  hb.stamp_ns(0);
  Counter c;
  c.name("observations");
  c.value(42);
  hb.counters().push_back(c);
  const std::string text = format_heartbeat(hb, 1'000'000'000);
  EXPECT_NE(text.find("mapper"), std::string::npos);
  EXPECT_NE(text.find("observations"), std::string::npos);
  EXPECT_NE(text.find("42"), std::string::npos);
}

}  // namespace
}  // namespace slam::ctl
