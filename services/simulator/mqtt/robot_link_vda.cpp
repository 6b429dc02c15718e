// RobotLinks, VDA 5050: a simulated robot as a VDA 5050 2.0 robot. It reports its pose (state and
// visualization; the standard carries no scans), keeps its connection topic (ONLINE, OFFLINE when
// it leaves, CONNECTIONBROKEN as its last will) and drives the fleet control's order node by node:
// a new order replaces an idle robot's, an update must start at the last released node, the horizon
// waits, cancelOrder stops it, startPause holds it where it is until stopPause; its state lists the
// instant actions it took. Orders arrive on paho threads and are applied by the loop.
#include <fmt/format.h>

#include <cmath>

#include "protocol/text_check.hpp"
#include "protocol/topic.hpp"
#include "simulator/mqtt/robot_link.hpp"

namespace slam::sim {
namespace {

// The simulation stops within its waypoint tolerance (5 cm); a node this close is passed.
constexpr double kNodeReachedM = 0.1;

std::span<const uint8_t> as_bytes(const std::string& text) {
  return {reinterpret_cast<const uint8_t*>(text.data()), text.size()};
}

std::int64_t wall_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

Status RobotLinks::add_vda(const std::string& robot_id, Endpoint& e, std::vector<std::string>& subscriptions,
                           std::optional<mqtt::Will>& will) {
  std::string fleet_id;
  if (auto s = protocol::vda_robot_id(kVdaManufacturer, robot_id, fleet_id); !s) return Error{s.detail()};
  VdaRobot& v = e.vda;
  protocol::vda_topic(vda_tree_, kVdaManufacturer, robot_id, protocol::VdaTopic::State, v.state_topic);
  protocol::vda_topic(vda_tree_, kVdaManufacturer, robot_id, protocol::VdaTopic::Visualization,
                      v.visualization_topic);
  protocol::vda_topic(vda_tree_, kVdaManufacturer, robot_id, protocol::VdaTopic::Connection,
                      v.connection_topic);
  subscriptions.resize(2);
  protocol::vda_topic(vda_tree_, kVdaManufacturer, robot_id, protocol::VdaTopic::Order, subscriptions[0]);
  protocol::vda_topic(vda_tree_, kVdaManufacturer, robot_id, protocol::VdaTopic::InstantActions,
                      subscriptions[1]);
  // The standard's last will: the broker tells the fleet control when the robot vanishes.
  std::string payload;
  protocol::encode_vda_connection({v.connection_headers++, wall_ns(), kVdaManufacturer, robot_id},
                                  protocol::VdaConnection::ConnectionBroken, payload);
  will = mqtt::Will{v.connection_topic, std::move(payload), 1, true};
  return {};
}

void RobotLinks::send_connection(Endpoint& e, const std::string& robot_id,
                                 protocol::VdaConnection connection) {
  protocol::encode_vda_connection({e.vda.connection_headers++, wall_ns(), kVdaManufacturer, robot_id},
                                  connection, text_);
  if (e.link->publish(e.vda.connection_topic, as_bytes(text_), 1, true))
    e.status_connects = e.link->connects();
}

void RobotLinks::publish_vda(Endpoint& e, const std::string& robot_id, const RobotReport& report,
                             bool driving) {
  VdaRobot& v = e.vda;
  if (e.link->connected() && e.status_connects != e.link->connects())
    send_connection(e, robot_id, protocol::VdaConnection::Online);
  const Vec2 at{report.reported_pose.x, report.reported_pose.y};
  bool passed = false;
  while (!v.nodes_left.empty() && v.nodes_left.front().released &&
         std::hypot(v.nodes_left.front().position.x - at.x, v.nodes_left.front().position.y - at.y) <
             kNodeReachedM) {
    v.last_node = std::move(v.nodes_left.front());
    v.nodes_left.erase(v.nodes_left.begin());
    passed = true;
  }
  if (passed) {
    v.state_due = true;
    steer(e, robot_id, steering_);
  }
  protocol::VdaRobotReport r{at.x,
                             at.y,
                             report.reported_pose.theta,
                             v.order.map_id.empty() ? std::string_view("map") : v.order.map_id,
                             driving,
                             v.order.order_id,
                             v.order.order_update_id,
                             v.last_node.node_id,
                             v.last_node.sequence_id,
                             v.nodes_left};
  r.paused = v.paused;
  r.action_states = v.actions_taken;
  const protocol::VdaHeader header{v.visualization_headers++, wall_ns(), kVdaManufacturer, robot_id};
  protocol::encode_vda_visualization(header, r, text_);
  send(e, v.visualization_topic, as_bytes(text_));
  if (!v.state_due && e.driving == driving && report.time_s - v.state_time_s < kVdaStatePeriodS) return;
  protocol::encode_vda_state({v.state_headers++, header.wall_ns, kVdaManufacturer, robot_id}, r, text_);
  send(e, v.state_topic, as_bytes(text_));
  v.state_due = false;
  v.state_time_s = report.time_s;
  e.driving = driving;
}

bool RobotLinks::on_vda_message(std::string_view topic, std::span<const uint8_t> payload) {
  protocol::VdaAddress address;
  if (auto s = protocol::parse_vda_command_topic(topic, vda_tree_, address);
      !s || address.manufacturer != kVdaManufacturer) {
    reject("?", s ? "unknown_robot" : std::string(protocol::reason_name(s.reason())),
           s ? "another manufacturer's topic" : s.detail());
    return false;
  }
  VdaCommand command{std::string(address.serial_number), {}, false, std::nullopt, {}};
  protocol::CodecStatus s;
  if (address.topic == protocol::VdaTopic::Order) {
    s = protocol::decode_vda_order(payload, settings_.limits, command.order);
    if (s && command.order.order_id.empty()) s = {protocol::RejectReason::BadText, "orderId is empty"};
  } else {
    std::vector<protocol::VdaInstantAction> actions;
    s = protocol::decode_vda_instant_actions(payload, settings_.limits, actions);
    for (const auto& a : actions) {
      command.action_ids.push_back(a.action_id);
      command.cancel = command.cancel || a.action_type == "cancelOrder";
      if (a.action_type == "startPause" || a.action_type == "stopPause")
        command.pause = a.action_type == "startPause";
    }
    if (s && !command.cancel && !command.pause) return true;  // nothing else is acted on
  }
  if (!s) {
    reject(command.robot_id, std::string(protocol::reason_name(s.reason())), s.detail());
    return false;
  }
  bump(waypoints_received_);
  std::lock_guard lock(intake_mutex_);
  if (vda_intake_.size() >= 1024) {
    bump(orders_dropped_);
    return false;
  }
  vda_intake_.push_back(std::move(command));
  return true;
}

void RobotLinks::take_vda(const VdaCommand& command, std::vector<WaypointOrder>& out) {
  const auto it = endpoints_.find(command.robot_id);
  if (it == endpoints_.end()) return;
  VdaRobot& v = it->second.vda;
  v.state_due = true;
  for (const std::string& id : command.action_ids) v.actions_taken.push_back({id, "FINISHED"});
  if (v.actions_taken.size() > kVdaActionsListed)
    v.actions_taken.erase(v.actions_taken.begin(), v.actions_taken.end() - kVdaActionsListed);
  if (command.cancel || command.pause) {
    if (command.cancel) v.nodes_left.clear();
    if (command.pause) v.paused = *command.pause;
    steer(it->second, command.robot_id, out);
    return;
  }
  const protocol::VdaOrder& o = command.order;
  const bool same = o.order_id == v.order.order_id;
  if (same && o.order_update_id <= v.order.order_update_id) return;  // taken already
  if (o.nodes.empty()) {
    reject(command.robot_id, "order", "an order without nodes");
    return;
  }
  if (same || !v.nodes_left.empty()) {
    // An update, or a new order while one runs: it must go on from the last released node.
    const protocol::VdaNode* base_end = &v.last_node;
    for (const protocol::VdaNode& n : v.nodes_left)
      if (n.released) base_end = &n;
    if (o.nodes[0].node_id != base_end->node_id || o.nodes[0].sequence_id != base_end->sequence_id) {
      reject(command.robot_id, "order",
             fmt::format("order {} update {} does not start at the last released node {}",
                         protocol::escape_for_log(o.order_id), o.order_update_id,
                         protocol::escape_for_log(base_end->node_id)));
      return;
    }
    std::erase_if(v.nodes_left, [](const protocol::VdaNode& n) { return !n.released; });
    v.nodes_left.insert(v.nodes_left.end(), o.nodes.begin() + 1, o.nodes.end());
  } else {
    v.nodes_left = o.nodes;
  }
  v.order.order_id = o.order_id;
  v.order.order_update_id = o.order_update_id;
  v.order.map_id = o.map_id;
  steer(it->second, command.robot_id, out);
}

void RobotLinks::steer(Endpoint& e, const std::string& robot_id, std::vector<WaypointOrder>& out) {
  VdaRobot& v = e.vda;
  std::optional<std::uint32_t> next;
  if (!v.paused && !v.nodes_left.empty() && v.nodes_left.front().released)
    next = v.nodes_left.front().sequence_id;
  if (next == v.steering_to && next) return;
  v.steering_to = next;
  WaypointOrder order{robot_id, std::nullopt};
  if (next) order.target = Vec2{v.nodes_left.front().position.x, v.nodes_left.front().position.y};
  out.push_back(std::move(order));
}

}  // namespace slam::sim
