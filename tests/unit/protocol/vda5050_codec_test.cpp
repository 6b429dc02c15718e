// VDA 5050: the robot topics of the configured tree, the robot messages read with every failure named,
// and the order and instantActions as the standard's 2.0 schema has them.
#include "protocol/vda5050_codec.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "payload.hpp"

namespace slam::protocol {
namespace {

using test::bytes;

const VdaTree kTree{};  // uagv/v2

// A message object: the header, then `members` (", ..." or empty). Built by appending: GCC 12 warns
// falsely (-Wrestrict) on "literal" + std::string&&.
std::string object(std::string_view members = "", std::string_view version = "2.0.0",
                   std::string_view serial = "agv-1") {
  std::string out = R"({"headerId": 7, "timestamp": "2026-11-28T10:00:00.000Z", "version": ")";
  out.append(version);
  out.append(R"(", "manufacturer": "Acme", "serialNumber": ")");
  out.append(serial);
  out.append("\"");
  out.append(members);
  out.append("}");
  return out;
}

std::string state_json() {
  return object(R"(, "orderId": "o1", "orderUpdateId": 2, "lastNodeId": "n2", "lastNodeSequenceId": 2,
    "nodeStates": [{"nodeId": "n4", "sequenceId": 4, "released": false}], "edgeStates": [],
    "driving": true, "operatingMode": "AUTOMATIC",
    "actionStates": [{"actionId": "a1", "actionType": "startPause", "actionStatus": "FINISHED"}],
    "batteryState": {"batteryCharge": 80, "charging": false},
    "safetyState": {"eStop": "NONE", "fieldViolation": false},
    "agvPosition": {"x": 1.5, "y": -2, "theta": 0.5, "mapId": "hall", "positionInitialized": true},
    "errors": [{"errorType": "orderUpdateError", "errorLevel": "WARNING", "errorDescription": "no stitching",
                "errorReferences": [{"referenceKey": "orderId", "referenceValue": "o1"},
                                    {"referenceKey": "orderUpdateId", "referenceValue": "3"}]}])");
}

CodecStatus decode(VdaTopic topic, const std::string& json, VdaMessage& out) {
  return decode_vda_message(topic, {topic, "Acme", "agv-1"}, bytes(json), kTree, CodecLimits{}, out);
}

TEST(Vda5050Codec, ParsesTheRobotTopicsOfTheConfiguredTree) {
  VdaAddress a;
  ASSERT_TRUE(parse_vda_topic("uagv/v2/Acme/agv-1/state", kTree, a));
  EXPECT_EQ(a.topic, VdaTopic::State);
  EXPECT_EQ(a.manufacturer, "Acme");
  EXPECT_EQ(a.serial_number, "agv-1");
  for (const auto* topic : {"connection", "visualization", "factsheet"})
    EXPECT_TRUE(parse_vda_topic(std::string("uagv/v2/Acme/agv-1/") + topic, kTree, a)) << topic;
  // The fleet control's own topics, other trees and other shapes are not robot topics.
  for (const auto* topic :
       {"uagv/v2/Acme/agv-1/order", "uagv/v2/Acme/agv-1/instantActions", "uagv/v1/Acme/agv-1/state",
        "other/v2/Acme/agv-1/state", "uagv/v2/Acme/state", "uagv/v2/Acme/agv-1/state/more"}) {
    const CodecStatus s = parse_vda_topic(topic, kTree, a);
    ASSERT_FALSE(s) << topic;
    EXPECT_EQ(s.reason(), RejectReason::UnknownTopic) << topic;
  }
  const CodecStatus empty = parse_vda_topic("uagv/v2/Acme//state", kTree, a);
  ASSERT_FALSE(empty);
  EXPECT_EQ(empty.reason(), RejectReason::BadRobotId);
  EXPECT_EQ(vda_robot_filters(kTree).front(), "uagv/v2/+/+/connection");
  EXPECT_EQ(vda_robot_filters(kTree).size(), 4u);
}

TEST(Vda5050Codec, RobotIdIsManufacturerColonSerialNumber) {
  std::string id;
  ASSERT_TRUE(vda_robot_id("Acme", "agv-1", id));
  EXPECT_EQ(id, "Acme:agv-1");
  const CodecStatus long_id = vda_robot_id(std::string(40, 'm'), std::string(40, 's'), id);
  ASSERT_FALSE(long_id);
  EXPECT_EQ(long_id.reason(), RejectReason::BadRobotId);
  std::string topic;
  vda_topic(kTree, "Acme", "agv-1", VdaTopic::InstantActions, topic);
  EXPECT_EQ(topic, "uagv/v2/Acme/agv-1/instantActions");
}

TEST(Vda5050Codec, StateCarriesPoseBatteryOrderProgressAndErrors) {
  VdaMessage m;
  ASSERT_TRUE(decode(VdaTopic::State, state_json(), m)) << decode(VdaTopic::State, state_json(), m).message();
  EXPECT_EQ(m.header_id, 7u);
  ASSERT_TRUE(m.has_position);
  EXPECT_TRUE(m.position_initialized);
  EXPECT_DOUBLE_EQ(m.x, 1.5);
  EXPECT_DOUBLE_EQ(m.y, -2.0);
  EXPECT_DOUBLE_EQ(m.theta, 0.5);
  EXPECT_EQ(m.map_id, "hall");
  EXPECT_FLOAT_EQ(m.battery, 0.8f);
  EXPECT_EQ(m.operating_mode, "AUTOMATIC");
  EXPECT_TRUE(m.driving);
  EXPECT_EQ(m.order_id, "o1");
  EXPECT_EQ(m.order_update_id, 2u);
  EXPECT_EQ(m.last_node_id, "n2");
  EXPECT_EQ(m.node_states, 1u);
  EXPECT_EQ(m.edge_states, 0u);
  ASSERT_EQ(m.errors.size(), 1u);
  EXPECT_EQ(m.errors[0].type, "orderUpdateError");
  EXPECT_EQ(m.errors[0].order_id, "o1");
  EXPECT_EQ(m.errors[0].order_update_id, "3");
  EXPECT_EQ(m.errors[0].description, "no stitching");
  EXPECT_FALSE(m.paused) << "paused is optional: absent, the robot is not paused";
  ASSERT_EQ(m.action_states.size(), 1u);
  EXPECT_EQ(m.action_states[0].action_id, "a1");
  EXPECT_EQ(m.action_states[0].status, "FINISHED");
}

TEST(Vda5050Codec, StateSaysWhetherTheRobotIsPaused) {
  VdaMessage m;
  std::string paused = state_json();
  paused.insert(paused.find("\"driving\""), R"("paused": true, )");
  ASSERT_TRUE(decode(VdaTopic::State, paused, m));
  EXPECT_TRUE(m.paused);
  std::string typo = state_json();
  typo.insert(typo.find("\"driving\""), R"("paused": "yes", )");
  EXPECT_EQ(decode(VdaTopic::State, typo, m).reason(), RejectReason::JsonType);
}

TEST(Vda5050Codec, ConnectionStatesAndTheirTypos) {
  VdaMessage m;
  ASSERT_TRUE(decode(VdaTopic::Connection, object(R"(, "connectionState": "CONNECTIONBROKEN")"), m));
  EXPECT_EQ(m.connection, VdaConnection::ConnectionBroken);
  ASSERT_TRUE(decode(VdaTopic::Connection, object(R"(, "connectionState": "ONLINE")"), m));
  EXPECT_EQ(m.connection, VdaConnection::Online);
  const CodecStatus typo = decode(VdaTopic::Connection, object(R"(, "connectionState": "online")"), m);
  ASSERT_FALSE(typo);
  EXPECT_EQ(typo.reason(), RejectReason::BadText);
}

TEST(Vda5050Codec, OtherMajorVersionsAreRefused) {
  VdaMessage m;
  for (const auto* version : {"1.1.0", "20.0.0", "2", "v2"}) {
    const CodecStatus s =
        decode(VdaTopic::Connection, object(R"(, "connectionState": "ONLINE")", version), m);
    ASSERT_FALSE(s) << version;
    EXPECT_EQ(s.reason(), RejectReason::BadVersion) << version;
  }
  EXPECT_TRUE(decode(VdaTopic::Connection, object(R"(, "connectionState": "ONLINE")", "2.1.0"), m));
}

TEST(Vda5050Codec, MalformedMessagesNameWhatIsWrong) {
  VdaMessage m;
  EXPECT_EQ(decode(VdaTopic::State, "{\"headerId\": ", m).reason(), RejectReason::JsonSyntax);
  EXPECT_EQ(decode(VdaTopic::State, "[]", m).reason(), RejectReason::JsonType);
  EXPECT_EQ(decode(VdaTopic::State, "", m).reason(), RejectReason::EmptyPayload);
  EXPECT_EQ(decode(VdaTopic::Visualization, R"({"version": "2.0.0"})", m).reason(),
            RejectReason::MissingField);
  const CodecStatus other_robot = decode(VdaTopic::Visualization, object("", "2.0.0", "agv-2"), m);
  EXPECT_EQ(other_robot.reason(), RejectReason::BadRobotId);
  const CodecStatus no_nodes = decode(VdaTopic::State, object(R"(, "orderId": "o1")"), m);
  EXPECT_EQ(no_nodes.reason(), RejectReason::MissingField);
  std::string no_status = state_json();
  no_status.replace(no_status.find("\"actionStatus\""), 14, "\"status\"");
  EXPECT_EQ(decode(VdaTopic::State, no_status, m).reason(), RejectReason::MissingField);
  std::string far = state_json();
  far.replace(far.find("\"x\": 1.5"), 8, "\"x\": 1e9");
  EXPECT_EQ(decode(VdaTopic::State, far, m).reason(), RejectReason::OutOfRange);
}

TEST(Vda5050Codec, VisualizationMayCarryNoPosition) {
  VdaMessage m;
  ASSERT_TRUE(decode(VdaTopic::Visualization, object(), m));
  EXPECT_FALSE(m.has_position);
  ASSERT_TRUE(decode(
      VdaTopic::Visualization,
      object(R"(, "agvPosition": {"x": 1, "y": 2, "theta": 0, "mapId": "m", "positionInitialized": false})"),
      m));
  EXPECT_TRUE(m.has_position);
  EXPECT_FALSE(m.position_initialized);
}

TEST(Vda5050Codec, TimestampIsIso8601UtcWithMilliseconds) {
  EXPECT_EQ(vda_timestamp(0), "1970-01-01T00:00:00.000Z");
  EXPECT_EQ(vda_timestamp(1'764'327'042'123'456'789), "2025-11-28T10:50:42.123Z");
}

TEST(Vda5050Codec, OrderHasReleasedBaseHorizonAndEdgesBetweenNodes) {
  VdaOrder order{
      "o1", 3, "hall", {{"n4", 4, true, {1, 2}}, {"n6", 6, true, {3, 2}}, {"n8", 8, false, {3, 5}}}};
  std::string text;
  ASSERT_TRUE(encode_vda_order({12, 0, "Acme", "agv-1"}, order, CodecLimits{}, text));
  const auto doc = nlohmann::json::parse(text);
  EXPECT_EQ(doc["headerId"], 12);
  EXPECT_EQ(doc["version"], "2.0.0");
  EXPECT_EQ(doc["timestamp"], "1970-01-01T00:00:00.000Z");
  EXPECT_EQ(doc["manufacturer"], "Acme");
  EXPECT_EQ(doc["serialNumber"], "agv-1");
  EXPECT_EQ(doc["orderId"], "o1");
  EXPECT_EQ(doc["orderUpdateId"], 3);
  ASSERT_EQ(doc["nodes"].size(), 3u);
  EXPECT_EQ(doc["nodes"][1]["nodeId"], "n6");
  EXPECT_EQ(doc["nodes"][1]["sequenceId"], 6);
  EXPECT_EQ(doc["nodes"][2]["released"], false);
  EXPECT_EQ(doc["nodes"][2]["nodePosition"]["y"], 5.0);
  EXPECT_EQ(doc["nodes"][2]["nodePosition"]["mapId"], "hall");
  EXPECT_TRUE(doc["nodes"][0]["actions"].is_array());
  ASSERT_EQ(doc["edges"].size(), 2u);
  EXPECT_EQ(doc["edges"][0]["edgeId"], "e5");
  EXPECT_EQ(doc["edges"][0]["sequenceId"], 5);
  EXPECT_EQ(doc["edges"][0]["startNodeId"], "n4");
  EXPECT_EQ(doc["edges"][0]["endNodeId"], "n6");
  EXPECT_EQ(doc["edges"][0]["released"], true);
  EXPECT_EQ(doc["edges"][1]["released"], false);

  order.nodes[1].position.x = 1e9;
  EXPECT_EQ(encode_vda_order({13, 0, "Acme", "agv-1"}, order, CodecLimits{}, text).reason(),
            RejectReason::OutOfRange);
}

TEST(Vda5050Codec, InstantActionsCarryTheirIdsAndTypes) {
  const VdaInstantAction cancel{"c1", "cancelOrder"};
  std::string text;
  encode_vda_instant_actions({0, 0, "Acme", "agv-1"}, std::span(&cancel, 1), text);
  const auto doc = nlohmann::json::parse(text);
  ASSERT_EQ(doc["instantActions"].size(), 1u);
  EXPECT_EQ(doc["instantActions"][0]["actionId"], "c1");
  EXPECT_EQ(doc["instantActions"][0]["actionType"], "cancelOrder");
  EXPECT_EQ(doc["instantActions"][0]["blockingType"], "HARD");
}

TEST(Vda5050Codec, TheRobotsSideReadsTheOrdersTheFleetControlWrites) {
  VdaAddress a;
  ASSERT_TRUE(parse_vda_command_topic("uagv/v2/Acme/agv-1/order", kTree, a));
  EXPECT_EQ(a.topic, VdaTopic::Order);
  EXPECT_EQ(a.serial_number, "agv-1");
  EXPECT_FALSE(parse_vda_command_topic("uagv/v2/Acme/agv-1/state", kTree, a));
  EXPECT_FALSE(parse_vda_command_topic("uagv/v2/Acme/x/y/order", kTree, a));
  EXPECT_EQ(vda_command_filter(kTree, "Acme", VdaTopic::InstantActions), "uagv/v2/Acme/+/instantActions");

  const VdaOrder sent{"o1", 2, "hall", {{"n4", 4, true, {1, 2}}, {"n6", 6, false, {3, 2.5}}}};
  std::string text;
  ASSERT_TRUE(encode_vda_order({1, 0, "Acme", "agv-1"}, sent, CodecLimits{}, text));
  VdaOrder read;
  ASSERT_TRUE(decode_vda_order(bytes(text), CodecLimits{}, read));
  EXPECT_EQ(read.order_id, "o1");
  EXPECT_EQ(read.order_update_id, 2u);
  EXPECT_EQ(read.map_id, "hall");
  ASSERT_EQ(read.nodes.size(), 2u);
  EXPECT_EQ(read.nodes[1].node_id, "n6");
  EXPECT_EQ(read.nodes[1].sequence_id, 6u);
  EXPECT_FALSE(read.nodes[1].released);
  EXPECT_EQ(read.nodes[1].position, (Point{3, 2.5}));
  EXPECT_EQ(decode_vda_order(bytes(R"({"orderId": "o", "orderUpdateId": 0, "nodes": [{"nodeId": "n0",
      "sequenceId": 0, "released": true}]})"),
                             CodecLimits{}, read)
                .reason(),
            RejectReason::MissingField);

  const VdaInstantAction cancel{"c1", "cancelOrder"};
  encode_vda_instant_actions({0, 0, "Acme", "agv-1"}, std::span(&cancel, 1), text);
  std::vector<VdaInstantAction> actions;
  ASSERT_TRUE(decode_vda_instant_actions(bytes(text), CodecLimits{}, actions));
  ASSERT_EQ(actions.size(), 1u);
  EXPECT_EQ(actions[0].action_type, "cancelOrder");
}

TEST(Vda5050Codec, WhatTheRobotsSideWritesTheFleetControlReads) {
  const std::vector<VdaNode> left{{"n6", 6, false, {3, 2}}};
  const std::vector<VdaActionState> taken{{"a1", "FINISHED"}};
  const VdaRobotReport report{1.5, -2, 0.25, "hall", true, "o1", 2, "n4", 4, left, 0.5f, true, taken};
  std::string text;
  encode_vda_state({5, 0, "Acme", "agv-1"}, report, text);
  VdaMessage m;
  ASSERT_TRUE(decode(VdaTopic::State, text, m)) << decode(VdaTopic::State, text, m).message();
  EXPECT_DOUBLE_EQ(m.x, 1.5);
  EXPECT_EQ(m.map_id, "hall");
  EXPECT_EQ(m.order_id, "o1");
  EXPECT_EQ(m.last_node_id, "n4");
  EXPECT_EQ(m.node_states, 1u);
  EXPECT_TRUE(m.driving);
  EXPECT_TRUE(m.paused);
  ASSERT_EQ(m.action_states.size(), 1u);
  EXPECT_EQ(m.action_states[0].action_id, "a1");
  EXPECT_FLOAT_EQ(m.battery, 0.5f);
  encode_vda_visualization({6, 0, "Acme", "agv-1"}, report, text);
  ASSERT_TRUE(decode(VdaTopic::Visualization, text, m));
  EXPECT_DOUBLE_EQ(m.theta, 0.25);
  encode_vda_connection({7, 0, "Acme", "agv-1"}, VdaConnection::Offline, text);
  ASSERT_TRUE(decode(VdaTopic::Connection, text, m));
  EXPECT_EQ(m.connection, VdaConnection::Offline);
}

}  // namespace
}  // namespace slam::protocol
