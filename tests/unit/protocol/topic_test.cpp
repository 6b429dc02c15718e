// Topic classification, robot id rules and outbound topic construction.
#include "protocol/topic.hpp"

#include <gtest/gtest.h>

#include <string>

namespace slam::protocol {
namespace {

TEST(ParseTopic, ClassifiesEveryKind) {
  struct Case {
    const char* topic;
    TopicKind kind;
    const char* id;
  };
  for (const Case& c : {Case{"v1/robot/r1/adv", TopicKind::V1Adv, "r1"},
                        Case{"v2/robot/bot-7/pose", TopicKind::V2Pose, "bot-7"},
                        Case{"v2/robot/bot-7/points", TopicKind::V2Points, "bot-7"},
                        Case{"v2/robot/bot-7/scan", TopicKind::V2Scan, "bot-7"},
                        Case{"v2/robot/Łódź 3/status", TopicKind::V2Status, "Łódź 3"}}) {
    ParsedTopic parsed;
    const CodecStatus status = parse_topic(c.topic, parsed);
    ASSERT_TRUE(status.is_ok()) << c.topic << ": " << status.message();
    EXPECT_EQ(parsed.kind, c.kind);
    EXPECT_EQ(parsed.robot_id, c.id);
  }
}

TEST(ParseTopic, UnknownTopics) {
  for (const char* topic :
       {"", "v1", "v1/robot/", "v1/robot/r1", "v1/robot/r1/cmd", "v1/server/r1/cmd", "v2/robot/r1/adv",
        "v2/robot/r1/Pose", "v2/robot/r1/", "v3/robot/r1/pose", "/v1/robot/r1/adv", "V1/robot/r1/adv",
        "v2/server/r1/waypoint", "v1/robot/r1/adv/"}) {
    ParsedTopic parsed;
    const CodecStatus status = parse_topic(topic, parsed);
    ASSERT_FALSE(status.is_ok()) << topic;
    EXPECT_EQ(status.reason(), RejectReason::UnknownTopic) << topic;
  }
}

TEST(ParseTopic, BadRobotIds) {
  for (const std::string& topic :
       {std::string("v1/robot//adv"), std::string("v1/robot/+/adv"), std::string("v2/robot/#/pose"),
        std::string("v1/robot/a/b/adv"), std::string("v2/robot/a\xFF/scan"), std::string("v1/robot/a\nb/adv"),
        std::string("v1/robot/*/adv"), std::string("v1/robot/") + std::string(65, 'x') + "/adv",
        std::string("v1/robot/a\0b/adv", 16)}) {
    ParsedTopic parsed;
    const CodecStatus status = parse_topic(topic, parsed);
    ASSERT_FALSE(status.is_ok()) << topic;
    EXPECT_EQ(status.reason(), RejectReason::BadRobotId) << topic;
  }
}

TEST(ParseTopic, FailureLeavesOutputUntouched) {
  ParsedTopic parsed{TopicKind::V2Scan, "keep"};
  EXPECT_FALSE(parse_topic("v1/robot/+/adv", parsed).is_ok());
  EXPECT_EQ(parsed.kind, TopicKind::V2Scan);
  EXPECT_EQ(parsed.robot_id, "keep");
}

TEST(ValidateRobotId, LengthLimitIsInclusive) {
  EXPECT_TRUE(validate_robot_id(std::string(64, 'a')).is_ok());
  const CodecStatus status = validate_robot_id(std::string(65, 'a'));
  EXPECT_EQ(status.reason(), RejectReason::BadRobotId);
  EXPECT_NE(status.detail().find("65 bytes"), std::string::npos) << status.detail();
}

TEST(ValidateRobotId, DetailNamesTheCharacterAndEscapesBadBytes) {
  EXPECT_NE(validate_robot_id("ab+c").detail().find("'+' at byte 2"), std::string::npos);
  const CodecStatus utf = validate_robot_id("ab\xFE");
  EXPECT_NE(utf.detail().find("invalid UTF-8 at byte 2"), std::string::npos) << utf.detail();
  EXPECT_NE(utf.detail().find("ab\\xfe"), std::string::npos) << utf.detail();
}

TEST(OutboundTopics, BuildEachTree) {
  std::string topic;
  ASSERT_TRUE(v1_command_topic("r1", topic).is_ok());
  EXPECT_EQ(topic, "v1/server/r1/cmd");
  ASSERT_TRUE(v2_waypoint_topic("r1", topic).is_ok());
  EXPECT_EQ(topic, "v2/server/r1/waypoint");
  ASSERT_TRUE(v2_path_topic("r1", topic).is_ok());
  EXPECT_EQ(topic, "v2/server/r1/path");
}

TEST(OutboundTopics, RefuseBadIds) {
  std::string topic = "unchanged";
  EXPECT_EQ(v1_command_topic("a/b", topic).reason(), RejectReason::BadRobotId);
  EXPECT_EQ(v2_waypoint_topic("", topic).reason(), RejectReason::BadRobotId);
  EXPECT_EQ(v2_path_topic("#", topic).reason(), RejectReason::BadRobotId);
  EXPECT_EQ(topic, "unchanged");
}

TEST(TopicKind, NamesAndVersion) {
  EXPECT_EQ(topic_kind_name(TopicKind::V1Adv), "v1_adv");
  EXPECT_EQ(topic_kind_name(TopicKind::V2Scan), "v2_scan");
  EXPECT_TRUE(is_v1(TopicKind::V1Adv));
  EXPECT_FALSE(is_v1(TopicKind::V2Status));
}

TEST(Filters, CoverTheParsedTrees) {
  EXPECT_EQ(kV1RobotFilter, "v1/robot/+/adv");
  EXPECT_EQ(kV2RobotFilter, "v2/robot/+/+");
}

}  // namespace
}  // namespace slam::protocol
