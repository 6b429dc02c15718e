// The VDA 5050 robot's side, as the simulator's VDA robots speak it: orders and instantActions
// decoded, state, visualization and connection encoded.
#include "protocol/json_fields.hpp"
#include "protocol/vda5050_codec.hpp"
#include "protocol/vda5050_fields.hpp"

namespace slam::protocol {

using json_fields::Json;

namespace {

Json position_json(const VdaRobotReport& r) {
  return {{"x", r.x}, {"y", r.y}, {"theta", r.theta}, {"mapId", r.map_id}, {"positionInitialized", true}};
}

CodecStatus read_node(const Json& node, std::size_t i, const CodecLimits& limits, VdaNode& out) {
  if (auto s = json_fields::expect_object(node, {"nodes", i}); !s) return s;
  if (auto s = json_fields::member_text(node, "nodeId", {"nodes", i, "nodeId"}, vda5050_fields::kMaxTextBytes,
                                        out.node_id);
      !s)
    return s;
  if (auto s = json_fields::member_uint32(node, "sequenceId", {"nodes", i, "sequenceId"}, out.sequence_id);
      !s)
    return s;
  if (auto s = json_fields::member_bool(node, "released", {"nodes", i, "released"}, out.released); !s)
    return s;
  const Json* position = nullptr;
  if (auto s = json_fields::require(node, "nodePosition", {"nodes", i, "nodePosition"}, position); !s)
    return s;
  if (auto s = json_fields::expect_object(*position, {"nodes", i, "nodePosition"}); !s) return s;
  const double c = limits.max_abs_coordinate_m;
  if (auto s = json_fields::member_number(*position, "x", {"nodes", i, "nodePosition.x"}, c, out.position.x);
      !s)
    return s;
  return json_fields::member_number(*position, "y", {"nodes", i, "nodePosition.y"}, c, out.position.y);
}

}  // namespace

CodecStatus decode_vda_order(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                             VdaOrder& out) {
  Json doc;
  if (auto s = json_fields::parse_object(payload, limits, doc); !s) return s;
  if (auto s = vda5050_fields::read_order_identity(doc, out.order_id, out.order_update_id); !s) return s;
  const Json* nodes = nullptr;
  if (auto s = json_fields::member_array(doc, "nodes", {"nodes"}, limits, nodes); !s) return s;
  out.nodes.resize(nodes->size());
  for (std::size_t i = 0; i < nodes->size(); ++i)
    if (auto s = read_node((*nodes)[i], i, limits, out.nodes[i]); !s) return s;
  if (!out.nodes.empty()) {
    const Json& first = (*nodes)[0]["nodePosition"];
    if (auto s = json_fields::member_text(first, "mapId", {"nodes", 0, "nodePosition.mapId"},
                                          vda5050_fields::kMaxTextBytes, out.map_id);
        !s)
      return s;
  }
  return CodecStatus::ok();
}

CodecStatus decode_vda_instant_actions(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                                       std::vector<VdaInstantAction>& out) {
  Json doc;
  if (auto s = json_fields::parse_object(payload, limits, doc); !s) return s;
  const Json* actions = nullptr;
  if (auto s = json_fields::member_array(doc, "instantActions", {"instantActions"}, limits, actions); !s)
    return s;
  out.resize(actions->size());
  for (std::size_t i = 0; i < actions->size(); ++i) {
    const Json& a = (*actions)[i];
    if (auto s = json_fields::expect_object(a, {"instantActions", i}); !s) return s;
    if (auto s = json_fields::member_text(a, "actionId", {"instantActions", i, "actionId"},
                                          vda5050_fields::kMaxTextBytes, out[i].action_id);
        !s)
      return s;
    if (auto s = json_fields::member_text(a, "actionType", {"instantActions", i, "actionType"},
                                          vda5050_fields::kMaxTextBytes, out[i].action_type);
        !s)
      return s;
  }
  return CodecStatus::ok();
}

void encode_vda_state(const VdaHeader& header, const VdaRobotReport& report, std::string& out) {
  Json doc = Json::object();
  vda5050_fields::append_header(doc, header);
  doc["orderId"] = report.order_id;
  doc["orderUpdateId"] = report.order_update_id;
  doc["lastNodeId"] = report.last_node_id;
  doc["lastNodeSequenceId"] = report.last_node_sequence_id;
  Json nodes = Json::array();
  for (const VdaNode& n : report.nodes_left)
    nodes.push_back({{"nodeId", n.node_id}, {"sequenceId", n.sequence_id}, {"released", n.released}});
  doc["nodeStates"] = std::move(nodes);
  doc["edgeStates"] = Json::array();
  doc["driving"] = report.driving;
  doc["paused"] = report.paused;
  Json actions = Json::array();
  for (const VdaActionState& a : report.action_states)
    actions.push_back({{"actionId", a.action_id}, {"actionStatus", a.status}});
  doc["actionStates"] = std::move(actions);
  doc["batteryState"] = {{"batteryCharge", report.battery * 100.0}, {"charging", false}};
  doc["operatingMode"] = "AUTOMATIC";
  doc["errors"] = Json::array();
  doc["safetyState"] = {{"eStop", "NONE"}, {"fieldViolation", false}};
  doc["agvPosition"] = position_json(report);
  out = doc.dump();
}

void encode_vda_visualization(const VdaHeader& header, const VdaRobotReport& report, std::string& out) {
  Json doc = Json::object();
  vda5050_fields::append_header(doc, header);
  doc["agvPosition"] = position_json(report);
  out = doc.dump();
}

void encode_vda_connection(const VdaHeader& header, VdaConnection connection, std::string& out) {
  Json doc = Json::object();
  vda5050_fields::append_header(doc, header);
  doc["connectionState"] = connection == VdaConnection::Online    ? "ONLINE"
                           : connection == VdaConnection::Offline ? "OFFLINE"
                                                                  : "CONNECTIONBROKEN";
  out = doc.dump();
}

}  // namespace slam::protocol
