// Robot-side topics: the names a robot publishes on, and inbound command topic classification.
#include "protocol/robot_topics.hpp"

#include <gtest/gtest.h>

#include <string>

#include "protocol/topic.hpp"

namespace slam::protocol {
namespace {

TEST(RobotTopics, BuildEachAndTheGatewayParsesThem) {
  std::string out;
  ASSERT_TRUE(v1_adv_topic("r1", out).is_ok());
  EXPECT_EQ(out, "v1/robot/r1/adv");
  ParsedTopic parsed;
  ASSERT_TRUE(parse_topic(out, parsed).is_ok());
  EXPECT_EQ(parsed.kind, TopicKind::V1Adv);

  ASSERT_TRUE(v2_pose_topic("r1", out).is_ok());
  EXPECT_EQ(out, "v2/robot/r1/pose");
  ASSERT_TRUE(v2_scan_topic("r1", out).is_ok());
  EXPECT_EQ(out, "v2/robot/r1/scan");
  ASSERT_TRUE(parse_topic(out, parsed).is_ok());
  EXPECT_EQ(parsed.kind, TopicKind::V2Scan);
  ASSERT_TRUE(v2_status_topic("r1", out).is_ok());
  EXPECT_EQ(out, "v2/robot/r1/status");
  ASSERT_TRUE(parse_topic(out, parsed).is_ok());
  EXPECT_EQ(parsed.kind, TopicKind::V2Status);
}

TEST(RobotTopics, RefuseBadIdsAndLeaveOutputUntouched) {
  std::string out = "kept";
  EXPECT_EQ(v1_adv_topic("a/b", out).reason(), RejectReason::BadRobotId);
  EXPECT_EQ(v2_scan_topic("", out).reason(), RejectReason::BadRobotId);
  EXPECT_EQ(v2_status_topic("#", out).reason(), RejectReason::BadRobotId);
  EXPECT_EQ(out, "kept");
}

TEST(ParseCommandTopic, ClassifiesWhatTheGatewaySends) {
  std::string topic;
  ParsedCommandTopic parsed;
  ASSERT_TRUE(v1_command_topic("sim-1", topic).is_ok());
  ASSERT_TRUE(parse_command_topic(topic, parsed).is_ok());
  EXPECT_EQ(parsed.kind, CommandKind::V1Waypoint);
  EXPECT_EQ(parsed.robot_id, "sim-1");
  ASSERT_TRUE(v2_waypoint_topic("robot \xC3\xA9", topic).is_ok());
  ASSERT_TRUE(parse_command_topic(topic, parsed).is_ok());
  EXPECT_EQ(parsed.kind, CommandKind::V2Waypoint);
  EXPECT_EQ(parsed.robot_id, "robot \xC3\xA9");
  ASSERT_TRUE(v2_path_topic("x", topic).is_ok());
  ASSERT_TRUE(parse_command_topic(topic, parsed).is_ok());
  EXPECT_EQ(parsed.kind, CommandKind::V2Path);
}

TEST(ParseCommandTopic, RejectsOtherTopicsAndBadIds) {
  ParsedCommandTopic parsed;
  for (const char* topic : {"", "v1/server/cmd", "v1/robot/r1/adv", "v2/server/r1/cmd",
                            "v1/server/r1/waypoint", "v2/server/r1/Path", "x/v1/server/r1/cmd"})
    EXPECT_EQ(parse_command_topic(topic, parsed).reason(), RejectReason::UnknownTopic) << topic;
  for (const char* topic :
       {"v1/server//cmd", "v1/server/a/b/cmd", "v2/server/*/waypoint", "v2/server/+/path"})
    EXPECT_EQ(parse_command_topic(topic, parsed).reason(), RejectReason::BadRobotId) << topic;
}

TEST(CommandFilters, MatchTheCommandTrees) {
  EXPECT_EQ(kV1CommandFilter, "v1/server/+/cmd");
  EXPECT_EQ(kV2WaypointFilter, "v2/server/+/waypoint");
  EXPECT_EQ(kV2PathFilter, "v2/server/+/path");
}

}  // namespace
}  // namespace slam::protocol
