// InboundDecoder + apply_inbound: topic + payload through to the registry; rejections leave nothing behind.
#include "gateway/core/inbound_decoder.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace slam::gateway {
namespace {

std::span<const std::uint8_t> bytes(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

const Instant kNow{1'700'000'000'000'000'000, 1'000'000'000};

class InboundDecoderTest : public ::testing::Test {
 protected:
  // As the gateway does it: decoded on the MQTT thread, recorded by the loop.
  InboundKind feed(const std::string& topic, const std::string& payload) {
    decoder.decode(topic, bytes(payload), kNow, message);
    result = apply_inbound(registry, message);
    return result.kind;
  }
  const protocol::DecodedObservation& observation() const { return message.message.observation; }
  RobotRegistry registry;
  InboundDecoder decoder{protocol::CodecLimits{}};
  InboundMessage message;
  InboundResult result;
};

TEST_F(InboundDecoderTest, V1AdvBecomesAnObservationInMetres) {
  const std::string payload("\x64\x00\x06\xff\x78\x00\x23\x00", 8);
  ASSERT_EQ(feed("v1/robot/r1/adv", payload), InboundKind::Observation);
  EXPECT_EQ(message.robot_id, "r1");
  EXPECT_EQ(message.protocol(), Protocol::V1);
  EXPECT_EQ(result.accepted.seq, 1u);
  EXPECT_DOUBLE_EQ(observation().x, 1.0);
  EXPECT_DOUBLE_EQ(observation().y, -2.5);
  ASSERT_EQ(observation().hits.size(), 1u);
  EXPECT_DOUBLE_EQ(observation().hits[0].x, 1.2);
  EXPECT_DOUBLE_EQ(observation().hits[0].y, 0.35);
  EXPECT_EQ(registry.find("r1")->protocol, Protocol::V1);
}

TEST_F(InboundDecoderTest, V2PoseAndStatus) {
  ASSERT_EQ(feed("v2/robot/r2/pose", R"({"x": 1.5, "y": -2.0, "heading": 0.3})"), InboundKind::Observation);
  EXPECT_EQ(message.protocol(), Protocol::V2);
  EXPECT_TRUE(observation().has_heading);
  ASSERT_EQ(feed("v2/robot/r2/status", R"({"battery": 0.5, "state": "exploring"})"), InboundKind::Status);
  EXPECT_EQ(registry.find("r2")->status, "exploring");
  EXPECT_EQ(registry.find("r2")->messages, 2u);
}

TEST_F(InboundDecoderTest, RejectionsNameTheReasonAndCountAgainstKnownRobots) {
  ASSERT_EQ(feed("v1/robot/r1/adv", std::string("\x01\x00\x02\x00", 4)), InboundKind::Observation);
  ASSERT_EQ(feed("v1/robot/r1/adv", std::string("\x01\x00\x02", 3)), InboundKind::Rejected);
  EXPECT_EQ(message.status.reason(), protocol::RejectReason::BadLength);
  EXPECT_EQ(registry.find("r1")->rejected, 1u);
  EXPECT_EQ(registry.find("r1")->messages, 1u);

  ASSERT_EQ(feed("v1/robot/new/adv", ""), InboundKind::Rejected);
  EXPECT_EQ(message.status.reason(), protocol::RejectReason::EmptyPayload);
  EXPECT_EQ(registry.find("new"), nullptr);

  ASSERT_EQ(feed("v3/robot/x/adv", "abcd"), InboundKind::Rejected);
  EXPECT_EQ(message.status.reason(), protocol::RejectReason::UnknownTopic);
  EXPECT_TRUE(message.robot_id.empty());

  ASSERT_EQ(feed("v1/robot/*/adv", "abcd"), InboundKind::Rejected);
  EXPECT_EQ(message.status.reason(), protocol::RejectReason::BadRobotId);

  ASSERT_EQ(feed("v2/robot/r2/pose", R"({"x": "1", "y": 2})"), InboundKind::Rejected);
  EXPECT_EQ(message.status.reason(), protocol::RejectReason::JsonType);
  EXPECT_EQ(registry.size(), 1u);
}

TEST_F(InboundDecoderTest, PointsBeforeAnyPoseAreMissingField) {
  ASSERT_EQ(feed("v2/robot/r/points", R"({"points": [[1, 2]]})"), InboundKind::Rejected);
  EXPECT_EQ(message.status.reason(), protocol::RejectReason::MissingField);
  EXPECT_EQ(registry.size(), 0u);
  ASSERT_EQ(feed("v2/robot/r/pose", R"({"x": 1, "y": 1})"), InboundKind::Observation);
  ASSERT_EQ(feed("v2/robot/r/points", R"({"points": [[1, 2]]})"), InboundKind::Observation);
  EXPECT_EQ(result.accepted.seq, 2u);
  EXPECT_DOUBLE_EQ(observation().x, 1.0);
}

TEST_F(InboundDecoderTest, AFullRegistryRefusesNewRobots) {
  RobotRegistry small(RegistryConfig{1'000'000'000, 1});
  decoder.decode("v1/robot/a/adv", bytes(std::string(4, '\0')), kNow, message);
  EXPECT_EQ(apply_inbound(small, message).kind, InboundKind::Observation);
  decoder.decode("v1/robot/b/adv", bytes(std::string(4, '\0')), kNow, message);
  EXPECT_EQ(apply_inbound(small, message).kind, InboundKind::Refused);
}

TEST_F(InboundDecoderTest, TheMessageKeepsTopicIdAndReceiveTimeAndReplacesEveryField) {
  ASSERT_EQ(feed("v2/robot/r/pose", R"({"x": 1, "y": 1})"), InboundKind::Observation);
  EXPECT_EQ(message.points(), 0u);
  ASSERT_EQ(feed("v2/robot/r/points", R"({"points": [[1, 2], [3, 4]]})"), InboundKind::Observation);
  EXPECT_EQ(message.topic, "v2/robot/r/points");
  EXPECT_EQ(message.robot_id, "r");
  EXPECT_EQ(message.received.mono_ns, kNow.mono_ns);
  EXPECT_EQ(message.points(), 2u);
  // A message on an unknown topic leaves nothing of the previous one behind.
  ASSERT_EQ(feed("elsewhere/x", "{}"), InboundKind::Rejected);
  EXPECT_TRUE(message.robot_id.empty());
  EXPECT_EQ(message.points(), 0u);
  EXPECT_TRUE(observation().hits.empty());
}

// A VDA 5050 message of robot Acme/agv-1: the header, then `members`.
std::string vda(std::string_view members) {
  std::string out =
      R"({"headerId": 1, "timestamp": "2026-11-28T10:00:00.000Z", "version": "2.0.0", "manufacturer": "Acme", )"
      R"("serialNumber": "agv-1")";
  out.append(members);
  out.append("}");
  return out;
}

const std::string kVdaState =
    vda(R"(, "orderId": "", "orderUpdateId": 0, "lastNodeId": "", "lastNodeSequenceId": 0,
    "nodeStates": [], "edgeStates": [], "driving": false, "operatingMode": "AUTOMATIC", "errors": [],
    "actionStates": [],
    "batteryState": {"batteryCharge": 40}, "agvPosition": {"x": 2, "y": 3, "theta": 0.5, "mapId": "hall",
    "positionInitialized": true})");

class VdaInboundTest : public InboundDecoderTest {
 protected:
  VdaInboundTest() { decoder = InboundDecoder{protocol::CodecLimits{}, VdaInbound{true, {}, {}}}; }
};

TEST_F(VdaInboundTest, AStateIsTheRobotsPoseBatteryAndOperatingMode) {
  ASSERT_EQ(feed("uagv/v2/Acme/agv-1/state", kVdaState), InboundKind::Observation)
      << message.status.message();
  EXPECT_EQ(message.robot_id, "Acme:agv-1");
  EXPECT_EQ(message.protocol(), Protocol::Vda5050);
  EXPECT_EQ(message.vda_address().serial_number, "agv-1");
  const RobotRecord* r = registry.find("Acme:agv-1");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->protocol, Protocol::Vda5050);
  EXPECT_DOUBLE_EQ(r->x, 2.0);
  EXPECT_DOUBLE_EQ(r->theta, 0.5);
  EXPECT_FLOAT_EQ(r->battery, 0.4f);
  EXPECT_EQ(r->status, "AUTOMATIC");
  EXPECT_EQ(r->messages, 1u);
}

TEST_F(VdaInboundTest, ABrokenConnectionTurnsTheRobotOffline) {
  // Heard first through its connection, a robot is not recorded yet: it has no pose to be at.
  ASSERT_EQ(feed("uagv/v2/Acme/agv-1/connection", vda(R"(, "connectionState": "ONLINE")")),
            InboundKind::Status);
  EXPECT_EQ(registry.find("Acme:agv-1"), nullptr);
  ASSERT_EQ(feed("uagv/v2/Acme/agv-1/state", kVdaState), InboundKind::Observation);
  ASSERT_EQ(feed("uagv/v2/Acme/agv-1/connection", vda(R"(, "connectionState": "CONNECTIONBROKEN")")),
            InboundKind::Status);
  EXPECT_TRUE(result.accepted.went_offline);
  EXPECT_EQ(registry.find("Acme:agv-1")->presence, Presence::Offline);
}

TEST_F(VdaInboundTest, RejectionsCountAndAnUnlistedRobotIsNoRobot) {
  ASSERT_EQ(feed("uagv/v2/Acme/agv-1/state", kVdaState), InboundKind::Observation);
  ASSERT_EQ(feed("uagv/v2/Acme/agv-1/state", "{"), InboundKind::Rejected);
  EXPECT_EQ(message.status.reason(), protocol::RejectReason::JsonSyntax);
  EXPECT_EQ(registry.find("Acme:agv-1")->rejected, 1u);
  ASSERT_EQ(feed("uagv/v2/Acme/agv-1/order", "{}"), InboundKind::Rejected);
  EXPECT_EQ(message.status.reason(), protocol::RejectReason::UnknownTopic);

  decoder = InboundDecoder{protocol::CodecLimits{}, VdaInbound{true, {}, {"Acme/agv-2"}}};
  ASSERT_EQ(feed("uagv/v2/Acme/agv-1/state", kVdaState), InboundKind::Rejected);
  EXPECT_EQ(message.status.reason(), protocol::RejectReason::UnknownRobot);
  EXPECT_TRUE(message.robot_id.empty());
  // Off: the tree is no robot tree at all.
  decoder = InboundDecoder{protocol::CodecLimits{}};
  ASSERT_EQ(feed("uagv/v2/Acme/agv-1/state", kVdaState), InboundKind::Rejected);
  EXPECT_EQ(message.status.reason(), protocol::RejectReason::UnknownTopic);
}

}  // namespace
}  // namespace slam::gateway
