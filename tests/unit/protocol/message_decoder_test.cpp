// The single inbound entry point: topic kind selects the decoder, the other output is cleared.
#include "protocol/message_decoder.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "payload.hpp"

namespace slam::protocol {
namespace {

using test::bytes;

TEST(DecodeMessage, TopicToObservation) {
  ParsedTopic topic;
  ASSERT_TRUE(parse_topic("v1/robot/r1/adv", topic).is_ok());
  const std::vector<std::uint8_t> payload = {0x64, 0x00, 0x06, 0xFF, 0x00, 0x00, 0x00, 0x00};
  DecodedMessage out;
  ASSERT_TRUE(decode_message(topic.kind, payload, {}, out).is_ok());
  EXPECT_EQ(out.kind, TopicKind::V1Adv);
  EXPECT_DOUBLE_EQ(out.observation.x, 1.0);
  EXPECT_EQ(out.observation.hits.size(), 1u);
}

TEST(DecodeMessage, EachV2Kind) {
  DecodedMessage out;
  ASSERT_TRUE(decode_message(TopicKind::V2Pose, bytes(R"({"x":1,"y":2,"heading":0})"), {}, out).is_ok());
  EXPECT_TRUE(out.observation.has_heading);
  ASSERT_TRUE(decode_message(TopicKind::V2Points, bytes(R"({"points":[[1,2]]})"), {}, out).is_ok());
  EXPECT_EQ(out.observation.hits.size(), 1u);
  ASSERT_TRUE(decode_message(
                  TopicKind::V2Scan,
                  bytes(R"({"pose":{"x":0,"y":0,"heading":0},"angles":[0],"ranges":[null],"max_range":3})"),
                  {}, out)
                  .is_ok());
  EXPECT_EQ(out.observation.misses.size(), 1u);
  ASSERT_TRUE(decode_message(TopicKind::V2Status, bytes(R"({"state":"offline"})"), {}, out).is_ok());
  EXPECT_EQ(out.kind, TopicKind::V2Status);
  EXPECT_TRUE(out.status.offline);
  EXPECT_TRUE(out.observation.misses.empty());  // the previous message's data is gone
}

TEST(DecodeMessage, WrongProtocolForKindIsRejected) {
  DecodedMessage out;
  EXPECT_EQ(decode_message(TopicKind::V1Adv, bytes(R"({"x":1,"y":2})"), {}, out).reason(),
            RejectReason::BadLength);
  EXPECT_EQ(decode_message(TopicKind::V2Pose, bytes("\x64\x00\x06\xff"), {}, out).reason(),
            RejectReason::JsonSyntax);
}

}  // namespace
}  // namespace slam::protocol
