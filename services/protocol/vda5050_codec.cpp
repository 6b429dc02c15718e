// VDA 5050 topics, and the fleet control's side: the robot messages' decoding (bounded, every failure
// naming its field) and the order and instantActions encoding. The robot's side (what the simulator's
// VDA robots speak) is in vda5050_robot_codec.cpp.
#include "protocol/vda5050_codec.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <ctime>

#include "protocol/json_fields.hpp"
#include "protocol/text_check.hpp"
#include "protocol/topic.hpp"
#include "protocol/vda5050_fields.hpp"

namespace slam::protocol {
namespace {

using json_fields::FieldName;
using json_fields::Json;

constexpr std::array<VdaTopic, 4> kRobotTopics = {VdaTopic::Connection, VdaTopic::State,
                                                  VdaTopic::Visualization, VdaTopic::Factsheet};

CodecStatus unknown(std::string_view topic) {
  return {RejectReason::UnknownTopic, "topic '" + escape_for_log(topic) + "' is not a VDA 5050 robot topic"};
}

CodecStatus check_level(std::string_view level, std::string_view what) {
  if (level.empty()) return {RejectReason::BadRobotId, fmt::format("{} level is empty", what)};
  if (const auto problem = find_text_problem(level))
    return {RejectReason::BadRobotId, fmt::format("{} '{}' has {} at byte {}", what, escape_for_log(level),
                                                  problem->what, problem->offset)};
  return CodecStatus::ok();
}

// headerId, version (of the configured major version), manufacturer and serialNumber as in the topic.
CodecStatus read_header(const Json& doc, const VdaAddress& address, const VdaTree& tree, VdaMessage& out) {
  if (auto s = json_fields::member_uint32(doc, "headerId", {"headerId"}, out.header_id); !s) return s;
  std::string text;
  if (auto s = json_fields::member_text(doc, "version", {"version"}, 32, text); !s) return s;
  // "v2" accepts "2.0.0", "2.1.0", ...: minor versions add optional members only.
  const std::string_view major = std::string_view(tree.major_version).substr(1);
  if (!text.starts_with(major) || text.size() <= major.size() || text[major.size()] != '.')
    return {RejectReason::BadVersion,
            fmt::format("version is '{}', this fleet control speaks {}.x", escape_for_log(text), major)};
  if (auto s = json_fields::member_text(doc, "manufacturer", {"manufacturer"}, vda5050_fields::kMaxTextBytes,
                                        text);
      !s)
    return s;
  if (text != address.manufacturer)
    return {RejectReason::BadRobotId,
            fmt::format("manufacturer '{}' differs from the topic's '{}'", escape_for_log(text),
                        escape_for_log(address.manufacturer))};
  if (auto s = json_fields::member_text(doc, "serialNumber", {"serialNumber"}, vda5050_fields::kMaxTextBytes,
                                        text);
      !s)
    return s;
  if (text != address.serial_number)
    return {RejectReason::BadRobotId,
            fmt::format("serialNumber '{}' differs from the topic's '{}'", escape_for_log(text),
                        escape_for_log(address.serial_number))};
  return CodecStatus::ok();
}

CodecStatus read_connection(const Json& doc, VdaMessage& out) {
  std::string state;
  if (auto s = json_fields::member_text(doc, "connectionState", {"connectionState"}, 32, state); !s) return s;
  if (state == "ONLINE") {
    out.connection = VdaConnection::Online;
  } else if (state == "OFFLINE") {
    out.connection = VdaConnection::Offline;
  } else if (state == "CONNECTIONBROKEN") {
    out.connection = VdaConnection::ConnectionBroken;
  } else {
    return {RejectReason::BadText, fmt::format("connectionState is '{}', expected ONLINE, OFFLINE or "
                                               "CONNECTIONBROKEN",
                                               escape_for_log(state))};
  }
  return CodecStatus::ok();
}

// The optional agvPosition of state and visualization.
CodecStatus read_position(const Json& doc, const CodecLimits& limits, VdaMessage& out) {
  const Json* position = json_fields::find_optional(doc, "agvPosition");
  if (position == nullptr) return CodecStatus::ok();
  if (auto s = json_fields::expect_object(*position, {"agvPosition"}); !s) return s;
  const double c = limits.max_abs_coordinate_m;
  if (auto s =
          json_fields::member_number(*position, "x", {"agvPosition", FieldName::kNoIndex, "x"}, c, out.x);
      !s)
    return s;
  if (auto s =
          json_fields::member_number(*position, "y", {"agvPosition", FieldName::kNoIndex, "y"}, c, out.y);
      !s)
    return s;
  if (auto s = json_fields::member_number(*position, "theta", {"agvPosition", FieldName::kNoIndex, "theta"},
                                          limits.max_abs_angle_rad, out.theta);
      !s)
    return s;
  if (auto s = json_fields::member_text(*position, "mapId", {"agvPosition", FieldName::kNoIndex, "mapId"},
                                        vda5050_fields::kMaxTextBytes, out.map_id);
      !s)
    return s;
  if (auto s = json_fields::member_bool(*position, "positionInitialized",
                                        {"agvPosition", FieldName::kNoIndex, "positionInitialized"},
                                        out.position_initialized);
      !s)
    return s;
  out.has_position = true;
  return CodecStatus::ok();
}

// A description is free text: cut to the bound and stripped to printable ASCII for the log, never
// a reason to drop the state that carries it.
std::string description_of(const Json& error) {
  const Json* d = json_fields::find_optional(error, "errorDescription");
  if (d == nullptr || !d->is_string()) return {};
  return escape_for_log(d->get_ref<const std::string&>(), vda5050_fields::kMaxTextBytes);
}

CodecStatus read_errors(const Json& doc, const CodecLimits& limits, VdaMessage& out) {
  const Json* errors = nullptr;
  if (auto s = json_fields::member_array(doc, "errors", {"errors"}, limits, errors); !s) return s;
  out.errors.resize(errors->size());
  for (std::size_t i = 0; i < errors->size(); ++i) {
    const Json& e = (*errors)[i];
    VdaError& error = out.errors[i];
    if (auto s = json_fields::expect_object(e, {"errors", i}); !s) return s;
    if (auto s = json_fields::member_text(e, "errorType", {"errors", i, "errorType"},
                                          vda5050_fields::kMaxTextBytes, error.type);
        !s)
      return s;
    if (auto s = json_fields::member_text(e, "errorLevel", {"errors", i, "errorLevel"}, 32, error.level); !s)
      return s;
    error.description = description_of(e);
    error.order_id.clear();
    error.order_update_id.clear();
    const Json* references = json_fields::find_optional(e, "errorReferences");
    if (references == nullptr) continue;
    if (auto s = json_fields::expect_array(*references, {"errors", i, "errorReferences"}); !s) return s;
    for (const Json& r : *references) {
      if (!r.is_object()) continue;
      const Json* key = json_fields::find(r, "referenceKey");
      const Json* value = json_fields::find(r, "referenceValue");
      if (key == nullptr || value == nullptr || !key->is_string() || !value->is_string()) continue;
      const auto& v = value->get_ref<const std::string&>();
      if (v.size() > vda5050_fields::kMaxTextBytes) continue;
      if (*key == "orderId") error.order_id = v;
      if (*key == "orderUpdateId") error.order_update_id = v;
    }
  }
  return CodecStatus::ok();
}

CodecStatus read_action_states(const Json& doc, const CodecLimits& limits, VdaMessage& out) {
  const Json* states = nullptr;
  if (auto s = json_fields::member_array(doc, "actionStates", {"actionStates"}, limits, states); !s) return s;
  out.action_states.resize(states->size());
  for (std::size_t i = 0; i < states->size(); ++i) {
    const Json& a = (*states)[i];
    VdaActionState& state = out.action_states[i];
    if (auto s = json_fields::expect_object(a, {"actionStates", i}); !s) return s;
    if (auto s = json_fields::member_text(a, "actionId", {"actionStates", i, "actionId"},
                                          vda5050_fields::kMaxTextBytes, state.action_id);
        !s)
      return s;
    if (auto s = json_fields::member_text(a, "actionStatus", {"actionStates", i, "actionStatus"}, 32,
                                          state.status);
        !s)
      return s;
  }
  return CodecStatus::ok();
}

CodecStatus read_state(const Json& doc, const CodecLimits& limits, VdaMessage& out) {
  if (auto s = read_position(doc, limits, out); !s) return s;
  if (auto s = vda5050_fields::read_order_identity(doc, out.order_id, out.order_update_id); !s) return s;
  if (auto s = json_fields::member_text(doc, "lastNodeId", {"lastNodeId"}, vda5050_fields::kMaxTextBytes,
                                        out.last_node_id);
      !s)
    return s;
  if (auto s = json_fields::member_uint32(doc, "lastNodeSequenceId", {"lastNodeSequenceId"},
                                          out.last_node_sequence_id);
      !s)
    return s;
  const Json* states = nullptr;
  if (auto s = json_fields::member_array(doc, "nodeStates", {"nodeStates"}, limits, states); !s) return s;
  out.node_states = states->size();
  if (auto s = json_fields::member_array(doc, "edgeStates", {"edgeStates"}, limits, states); !s) return s;
  out.edge_states = states->size();
  if (auto s = json_fields::member_bool(doc, "driving", {"driving"}, out.driving); !s) return s;
  if (json_fields::find_optional(doc, "paused") != nullptr)
    if (auto s = json_fields::member_bool(doc, "paused", {"paused"}, out.paused); !s) return s;
  // 32 bytes: it travels as the robot's status text (RobotState.status, string<32>).
  if (auto s = json_fields::member_text(doc, "operatingMode", {"operatingMode"}, kMaxStateBytes,
                                        out.operating_mode);
      !s)
    return s;
  if (out.operating_mode.empty()) return {RejectReason::BadText, "operatingMode is empty"};
  const Json* battery = nullptr;
  if (auto s = json_fields::require(doc, "batteryState", {"batteryState"}, battery); !s) return s;
  if (auto s = json_fields::expect_object(*battery, {"batteryState"}); !s) return s;
  double charge = 0.0;
  if (auto s = json_fields::member_number(
          *battery, "batteryCharge", {"batteryState", FieldName::kNoIndex, "batteryCharge"}, 100.0, charge);
      !s)
    return s;
  if (charge < 0.0)
    return {RejectReason::OutOfRange, fmt::format("batteryState.batteryCharge is {}, must be >= 0", charge)};
  out.battery = static_cast<float>(charge / 100.0);
  if (auto s = read_action_states(doc, limits, out); !s) return s;
  return read_errors(doc, limits, out);
}

}  // namespace

CodecStatus vda5050_fields::read_order_identity(const Json& doc, std::string& order_id,
                                                std::uint32_t& order_update_id) {
  if (auto s = json_fields::member_text(doc, "orderId", {"orderId"}, kMaxTextBytes, order_id); !s) return s;
  return json_fields::member_uint32(doc, "orderUpdateId", {"orderUpdateId"}, order_update_id);
}

void vda5050_fields::append_header(Json& doc, const VdaHeader& header) {
  doc["headerId"] = header.header_id;
  doc["timestamp"] = vda_timestamp(header.wall_ns);
  doc["version"] = kVdaVersion;
  doc["manufacturer"] = header.manufacturer;
  doc["serialNumber"] = header.serial_number;
}

std::string_view vda_topic_name(VdaTopic topic) {
  switch (topic) {
    case VdaTopic::Connection:
      return "connection";
    case VdaTopic::State:
      return "state";
    case VdaTopic::Visualization:
      return "visualization";
    case VdaTopic::Factsheet:
      return "factsheet";
    case VdaTopic::Order:
      return "order";
    case VdaTopic::InstantActions:
      return "instantActions";
  }
  return "unknown";
}

std::vector<std::string> vda_robot_filters(const VdaTree& tree) {
  std::vector<std::string> filters;
  for (const VdaTopic t : kRobotTopics)
    filters.push_back(
        fmt::format("{}/{}/+/+/{}", tree.interface_name, tree.major_version, vda_topic_name(t)));
  return filters;
}

CodecStatus parse_vda_topic(std::string_view topic, const VdaTree& tree, VdaAddress& out) {
  // <interface>/<major>/<manufacturer>/<serial>/<topic>: exactly five levels.
  std::array<std::string_view, 5> levels;
  std::size_t count = 0;
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = topic.find('/', start);
    if (count == levels.size()) return unknown(topic);
    levels[count++] = topic.substr(start, slash == std::string_view::npos ? slash : slash - start);
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  if (count != levels.size() || levels[0] != tree.interface_name || levels[1] != tree.major_version)
    return unknown(topic);
  bool found = false;
  for (const VdaTopic t : kRobotTopics) {
    if (levels[4] == vda_topic_name(t)) {
      out.topic = t;
      found = true;
    }
  }
  if (!found) return unknown(topic);
  if (auto s = check_level(levels[2], "manufacturer"); !s) return s;
  if (auto s = check_level(levels[3], "serialNumber"); !s) return s;
  out.manufacturer = levels[2];
  out.serial_number = levels[3];
  return CodecStatus::ok();
}

CodecStatus vda_robot_id(std::string_view manufacturer, std::string_view serial_number, std::string& out) {
  std::string id;
  id.reserve(manufacturer.size() + 1 + serial_number.size());
  id.append(manufacturer);
  id += ':';
  id.append(serial_number);
  if (auto s = validate_robot_id(id); !s) return s;
  out = std::move(id);
  return CodecStatus::ok();
}

void vda_topic(const VdaTree& tree, std::string_view manufacturer, std::string_view serial_number,
               VdaTopic topic, std::string& out) {
  out.assign(tree.interface_name);
  out += '/';
  out += tree.major_version;
  out += '/';
  out += manufacturer;
  out += '/';
  out += serial_number;
  out += '/';
  out += vda_topic_name(topic);
}

void VdaMessage::clear() {
  header_id = 0;
  connection = VdaConnection::Online;
  has_position = position_initialized = false;
  x = y = theta = 0.0;
  map_id.clear();
  battery = -1.0f;
  operating_mode.clear();
  driving = paused = false;
  order_id.clear();
  order_update_id = 0;
  last_node_id.clear();
  last_node_sequence_id = 0;
  node_states = edge_states = 0;
  errors.clear();
  action_states.clear();
}

CodecStatus decode_vda_message(VdaTopic topic, const VdaAddress& address,
                               std::span<const std::uint8_t> payload, const VdaTree& tree,
                               const CodecLimits& limits, VdaMessage& out) {
  out.clear();
  out.topic = topic;
  Json doc;
  if (auto s = json_fields::parse_object(payload, limits, doc); !s) return s;
  if (auto s = read_header(doc, address, tree, out); !s) return s;
  switch (topic) {
    case VdaTopic::Connection:
      return read_connection(doc, out);
    case VdaTopic::State:
      return read_state(doc, limits, out);
    case VdaTopic::Visualization:
      return read_position(doc, limits, out);
    case VdaTopic::Factsheet:
      return CodecStatus::ok();  // known, not read yet: the robot's header is all that is checked
    case VdaTopic::Order:
    case VdaTopic::InstantActions:
      break;
  }
  return {RejectReason::UnknownTopic, fmt::format("{} is a fleet control's topic", vda_topic_name(topic))};
}

std::string vda_timestamp(std::int64_t wall_ns) {
  const std::time_t seconds = static_cast<std::time_t>(wall_ns / 1'000'000'000);
  const auto millis = static_cast<int>((wall_ns % 1'000'000'000) / 1'000'000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:03}Z", utc.tm_year + 1900, utc.tm_mon + 1,
                     utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, millis);
}

CodecStatus encode_vda_order(const VdaHeader& header, const VdaOrder& order, const CodecLimits& limits,
                             std::string& out) {
  out.clear();
  if (order.nodes.size() > limits.max_points)
    return {RejectReason::TooManyPoints,
            fmt::format("order has {} nodes, limit {}", order.nodes.size(), limits.max_points)};
  Json doc = Json::object();
  vda5050_fields::append_header(doc, header);
  doc["orderId"] = order.order_id;
  doc["orderUpdateId"] = order.order_update_id;
  Json nodes = Json::array();
  Json edges = Json::array();
  for (std::size_t i = 0; i < order.nodes.size(); ++i) {
    const VdaNode& n = order.nodes[i];
    for (const double v : {n.position.x, n.position.y}) {
      if (!std::isfinite(v)) return {RejectReason::NonFinite, fmt::format("nodes[{}] has {}", i, v)};
      if (std::abs(v) > limits.max_abs_coordinate_m)
        return {RejectReason::OutOfRange,
                fmt::format("nodes[{}] has {}, limit +/-{}", i, v, limits.max_abs_coordinate_m)};
    }
    nodes.push_back({{"nodeId", n.node_id},
                     {"sequenceId", n.sequence_id},
                     {"released", n.released},
                     {"nodePosition", {{"x", n.position.x}, {"y", n.position.y}, {"mapId", order.map_id}}},
                     {"actions", Json::array()}});
    if (i == 0) continue;
    const VdaNode& from = order.nodes[i - 1];
    edges.push_back({{"edgeId", fmt::format("e{}", from.sequence_id + 1)},
                     {"sequenceId", from.sequence_id + 1},
                     {"released", n.released},
                     {"startNodeId", from.node_id},
                     {"endNodeId", n.node_id},
                     {"actions", Json::array()}});
  }
  doc["nodes"] = std::move(nodes);
  doc["edges"] = std::move(edges);
  out = doc.dump();
  return CodecStatus::ok();
}

void encode_vda_instant_actions(const VdaHeader& header, std::span<const VdaInstantAction> actions,
                                std::string& out) {
  Json doc = Json::object();
  vda5050_fields::append_header(doc, header);
  Json list = Json::array();
  // HARD: nothing else runs while the robot stops for them (the standard's choice for cancelOrder).
  for (const VdaInstantAction& a : actions)
    list.push_back({{"actionId", a.action_id}, {"actionType", a.action_type}, {"blockingType", "HARD"}});
  doc["instantActions"] = std::move(list);
  out = doc.dump();
}

CodecStatus parse_vda_command_topic(std::string_view topic, const VdaTree& tree, VdaAddress& out) {
  const std::string prefix = tree.interface_name + "/" + tree.major_version + "/";
  if (!topic.starts_with(prefix)) return unknown(topic);
  const std::string_view rest = topic.substr(prefix.size());
  const auto first = rest.find('/');
  const auto last = rest.rfind('/');
  if (first == std::string_view::npos || first == last) return unknown(topic);
  const std::string_view kind = rest.substr(last + 1);
  if (kind == vda_topic_name(VdaTopic::Order)) {
    out.topic = VdaTopic::Order;
  } else if (kind == vda_topic_name(VdaTopic::InstantActions)) {
    out.topic = VdaTopic::InstantActions;
  } else {
    return unknown(topic);
  }
  out.manufacturer = rest.substr(0, first);
  out.serial_number = rest.substr(first + 1, last - first - 1);
  if (auto s = check_level(out.manufacturer, "manufacturer"); !s) return s;
  if (out.serial_number.find('/') != std::string_view::npos) return unknown(topic);
  return check_level(out.serial_number, "serialNumber");
}

std::string vda_command_filter(const VdaTree& tree, std::string_view manufacturer, VdaTopic topic) {
  return fmt::format("{}/{}/{}/+/{}", tree.interface_name, tree.major_version, manufacturer,
                     vda_topic_name(topic));
}

}  // namespace slam::protocol
