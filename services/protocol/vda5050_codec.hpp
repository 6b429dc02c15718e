#pragma once
// VDA 5050 2.0, the VDA/VDMA interface between mobile robots and a fleet control, as the fleet control
// speaks it (docs/protocol.md, "VDA 5050"): the topic tree
// <interface>/<majorVersion>/<manufacturer>/<serialNumber>/<topic>, the robot's messages the gateway
// reads (connection, state, visualization, factsheet) and the two it writes (order, instantActions).
// Plain C++ over nlohmann-json; robots are known fleet-wide as "<manufacturer>:<serialNumber>".
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "protocol/codec_types.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::protocol {

enum class VdaTopic : std::uint8_t { Connection, State, Visualization, Factsheet, Order, InstantActions };

// "connection", "state", ...: the last topic level.
std::string_view vda_topic_name(VdaTopic topic);

// The first two topic levels: which interface and major version this fleet control speaks.
struct VdaTree {
  std::string interface_name = "uagv";
  std::string major_version = "v2";
};

// The robot -> fleet control subscriptions of `tree` (never order or instantActions: the fleet
// control publishes those into the same tree).
std::vector<std::string> vda_robot_filters(const VdaTree& tree);

// A parsed robot -> fleet control topic; the views point into the parsed topic.
struct VdaAddress {
  VdaTopic topic = VdaTopic::State;
  std::string_view manufacturer;
  std::string_view serial_number;
};

// UnknownTopic for anything but <interface>/<major>/<manufacturer>/<serial>/{connection,state,
// visualization,factsheet}; BadRobotId when a level is empty, holds control characters or bad UTF-8.
CodecStatus parse_vda_topic(std::string_view topic, const VdaTree& tree, VdaAddress& out);

// The fleet's robot id of a VDA robot, "<manufacturer>:<serialNumber>", checked by validate_robot_id().
CodecStatus vda_robot_id(std::string_view manufacturer, std::string_view serial_number, std::string& out);

// <interface>/<major>/<manufacturer>/<serial>/<topic>.
void vda_topic(const VdaTree& tree, std::string_view manufacturer, std::string_view serial_number,
               VdaTopic topic, std::string& out);

enum class VdaConnection : std::uint8_t { Online, Offline, ConnectionBroken };

// One entry of a state's "errors", with the order it names (its references), if any.
struct VdaError {
  std::string type;
  std::string level;
  std::string description;
  std::string order_id;         // reference "orderId", empty when none
  std::string order_update_id;  // reference "orderUpdateId", as the robot wrote it
};

// One entry of a state's "actionStates": an action the robot has taken, and how far it is with it
// (WAITING, INITIALIZING, RUNNING, PAUSED, FINISHED, FAILED).
struct VdaActionState {
  std::string action_id;
  std::string status;
};

// A robot message as the gateway reads it. Members a topic does not carry stay cleared.
struct VdaMessage {
  VdaTopic topic = VdaTopic::State;
  std::uint32_t header_id = 0;
  VdaConnection connection = VdaConnection::Online;  // connection
  // agvPosition (state, visualization): in the robot's own map, metres and radians.
  bool has_position = false;
  bool position_initialized = false;
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  std::string map_id;
  // state only
  float battery = -1.0f;       // batteryState.batteryCharge / 100, negative when absent
  std::string operating_mode;  // "AUTOMATIC", "MANUAL", ...
  bool driving = false;
  bool paused = false;  // "paused" (optional): a startPause holds it
  std::string order_id;
  std::uint32_t order_update_id = 0;
  std::string last_node_id;
  std::uint32_t last_node_sequence_id = 0;
  std::size_t node_states = 0;  // nodes of the order still to pass (base and horizon)
  std::size_t edge_states = 0;
  std::vector<VdaError> errors;
  std::vector<VdaActionState> action_states;

  void clear();
};

// Decodes a robot message of `topic` (connection, state, visualization or factsheet). The header's
// version must be of tree.major_version ("v2": "2.x.y"), else BadVersion; manufacturer and
// serialNumber must match the topic's levels, else BadRobotId.
CodecStatus decode_vda_message(VdaTopic topic, const VdaAddress& address,
                               std::span<const std::uint8_t> payload, const VdaTree& tree,
                               const CodecLimits& limits, VdaMessage& out);

// The header every message carries. headerId counts per topic and robot (the sender keeps it).
struct VdaHeader {
  std::uint32_t header_id = 0;
  std::int64_t wall_ns = 0;  // timestamp, Unix epoch
  std::string_view manufacturer;
  std::string_view serial_number;
};

inline constexpr std::string_view kVdaVersion = "2.0.0";

// A node of an order: released nodes are the base (the robot may drive there), the rest the horizon.
struct VdaNode {
  std::string node_id;
  std::uint32_t sequence_id = 0;  // even; the edge after it has sequence_id + 1
  bool released = true;
  Point position;  // in the robot's map
};

struct VdaOrder {
  std::string order_id;
  std::uint32_t order_update_id = 0;
  std::string map_id;
  std::vector<VdaNode> nodes;  // base first; an edge joins each node to the next
};

// ISO 8601 UTC with milliseconds: "2026-11-28T10:50:42.123Z".
std::string vda_timestamp(std::int64_t wall_ns);

// The order's JSON; edges "e<sequenceId>" between consecutive nodes, released with their end node.
// NonFinite / OutOfRange for a bad node position, TooManyPoints beyond limits.max_points nodes.
CodecStatus encode_vda_order(const VdaHeader& header, const VdaOrder& order, const CodecLimits& limits,
                             std::string& out);

// An instant action without parameters (cancelOrder, startPause, stopPause, stateRequest).
struct VdaInstantAction {
  std::string action_id;
  std::string action_type;
};

void encode_vda_instant_actions(const VdaHeader& header, std::span<const VdaInstantAction> actions,
                                std::string& out);

// The robot's side, as slam-simulator --protocol vda5050 speaks it.

// Fleet control -> robot topics (order, instantActions) of `tree`; UnknownTopic otherwise.
CodecStatus parse_vda_command_topic(std::string_view topic, const VdaTree& tree, VdaAddress& out);
// The subscription for `topic` of every robot of `manufacturer`.
std::string vda_command_filter(const VdaTree& tree, std::string_view manufacturer, VdaTopic topic);

// An order as the robot reads it: ids, and each node's id, sequence id, release and position (a node
// without a position is refused: the robot drives to positions).
CodecStatus decode_vda_order(std::span<const std::uint8_t> payload, const CodecLimits& limits, VdaOrder& out);
// The action types of an instantActions message, with their ids.
CodecStatus decode_vda_instant_actions(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                                       std::vector<VdaInstantAction>& out);

// What a robot reports of itself in its state and visualization.
struct VdaRobotReport {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  std::string_view map_id;
  bool driving = false;
  std::string_view order_id;
  std::uint32_t order_update_id = 0;
  std::string_view last_node_id;
  std::uint32_t last_node_sequence_id = 0;
  std::span<const VdaNode> nodes_left;              // node states: the order's nodes not passed yet
  float battery = 1.0f;                             // 0..1
  bool paused = false;                              // a startPause holds it
  std::span<const VdaActionState> action_states{};  // the instant actions it took
};

void encode_vda_state(const VdaHeader& header, const VdaRobotReport& report, std::string& out);
void encode_vda_visualization(const VdaHeader& header, const VdaRobotReport& report, std::string& out);
void encode_vda_connection(const VdaHeader& header, VdaConnection connection, std::string& out);

}  // namespace slam::protocol
