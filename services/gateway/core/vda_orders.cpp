// VdaOrders: base up to the planner's waypoint, horizon beyond, updates stitched at the last base node,
// halts as startPause (resumed by stopPause, or dropped by cancelOrder), and what the robot's state says
// of each.
#include "gateway/core/vda_orders.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace slam::gateway {
namespace {

using protocol::Point;

double distance(Point a, Point b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

std::string node_id(std::uint32_t sequence_id) {
  return fmt::format("n{}", sequence_id);
}

}  // namespace

VdaOrders::VdaOrders(protocol::VdaTree tree, protocol::CodecLimits limits, VdaOrdersConfig config)
    : tree_(std::move(tree)), limits_(limits), config_(config) {}

std::optional<VdaRejection> VdaOrders::take_message(std::string_view id, const protocol::VdaAddress& address,
                                                    const protocol::VdaMessage& message, bool& known) {
  std::optional<VdaRejection> rejection;
  auto it = robots_.find(id);
  if (it == robots_.end()) {
    known = robots_.size() < config_.max_robots;
    if (!known) return rejection;
    it = robots_.emplace(std::string(id), Robot{}).first;
  }
  known = true;
  Robot& robot = it->second;
  robot.manufacturer.assign(address.manufacturer);
  robot.serial_number.assign(address.serial_number);
  if (message.has_position) robot.map_id = message.map_id;
  if (message.topic == protocol::VdaTopic::State) take_state(robot, message, rejection);
  return rejection;
}

void VdaOrders::take_state(Robot& robot, const protocol::VdaMessage& state,
                           std::optional<VdaRejection>& rejection) {
  robot.has_state = true;
  robot.busy = state.node_states + state.edge_states > 0;
  robot.driving = state.driving;
  robot.robot_order_id = state.order_id;
  if (robot.unconfirmed && std::any_of(state.action_states.begin(), state.action_states.end(),
                                       [&](const protocol::VdaActionState& a) {
                                         return a.action_id == robot.unconfirmed->action.action_id;
                                       }))
    robot.unconfirmed.reset();  // taken, whatever became of it
  if (robot.cancelling && (!robot.busy || state.order_id != robot.order.order_id)) {
    // Cancelled (or the robot dropped it): the next path starts a new order from where it stands. A
    // robot may end its pause with the order (vda-5050-lib's does) or stay paused; stopPause is sent
    // with the next order only in the second case (the first refuses it: not paused).
    robot.cancelling = false;
    robot.holding = robot.holding && state.paused;
    robot.order = {};
  }
  if (robot.order.order_id.empty()) return;
  if (state.order_id == robot.order.order_id && state.order_update_id == robot.order.order_update_id) {
    robot.order_taken = true;
    robot.rejections = 0;
  }
  const std::string update = std::to_string(robot.order.order_update_id);
  for (const protocol::VdaError& e : state.errors) {
    if (e.order_id != robot.order.order_id || e.order_update_id != update) continue;
    const std::string key = robot.order.order_id + "/" + update;
    if (robot.rejection_reported == key) return;
    robot.rejection_reported = key;
    rejection = reject(robot, fmt::format("rejected: {} ({}): {}", e.type, e.level, e.description));
    // What it holds is the robot's business now: the next path starts afresh from the robot's state.
    robot.order = {};
    return;
  }
}

VdaRejection VdaOrders::reject(Robot& robot, const std::string& reason) {
  const Point destination = robot.order.nodes.back().position;
  const bool again = distance(destination, robot.rejected_destination) <= config_.same_node_m;
  robot.rejections = again ? robot.rejections + 1 : 1;
  robot.rejected_destination = destination;
  VdaRejection rejection{
      fmt::format("order {} update {} {}", robot.order.order_id, robot.order.order_update_id, reason),
      robot.rejections == config_.max_rejections};
  if (rejection.gave_up)
    rejection.text += fmt::format(
        "; {} orders to ({:.2f}, {:.2f}) rejected in a row, none is sent there again "
        "until the goal changes",
        robot.rejections, destination.x, destination.y);
  return rejection;
}

bool VdaOrders::gave_up_on(const Robot& robot, Point destination) const {
  return robot.rejections >= config_.max_rejections &&
         distance(destination, robot.rejected_destination) <= config_.same_node_m;
}

void VdaOrders::forget(std::string_view id) {
  if (const auto it = robots_.find(id); it != robots_.end()) robots_.erase(it);
}

protocol::CodecStatus VdaOrders::command(std::string_view id, std::optional<Point> position,
                                         std::span<const Point> path, const Instant& now,
                                         CommandMessages& out) {
  out.count = 0;
  const auto it = robots_.find(id);
  if (it == robots_.end())
    return {protocol::RejectReason::UnknownRobot,
            "no VDA 5050 message from the robot yet: its address is unknown"};
  Robot& robot = it->second;
  if (path.empty() || robot.cancelling) return protocol::CodecStatus::ok();

  const bool ours =
      !robot.order.order_id.empty() && (!robot.has_state || robot.robot_order_id == robot.order.order_id);
  if (robot.busy && !ours) {
    // An order of someone else's (a restarted gateway's), which a new order could only extend.
    cancel(robot, now, out.messages[0]);
    out.count = 1;
    return protocol::CodecStatus::ok();
  }
  const bool halt =
      path.size() == 1 && position && (robot.driving || robot.holding) && is_halt(robot, *position, path[0]);
  if (halt) {
    // Held where it is, its order kept for when the hold is over. Nothing under way: it stands already.
    if (!robot.holding && ours && (robot.busy || !robot.has_state)) {
      robot.holding = true;
      send_action(robot, "startPause", now, out.messages[0]);
      out.count = 1;
    }
    return protocol::CodecStatus::ok();
  }
  const bool resume = robot.holding;
  if (resume && robot.busy && !goes_on_to_base_end(robot, path[0])) {
    // Somewhere else now (a new goal after a stop): the held order is dropped, not driven on.
    cancel(robot, now, out.messages[0]);
    out.count = 1;
    return protocol::CodecStatus::ok();
  }

  bool changed = true;
  if (robot.order.order_id.empty()) {
    if (gave_up_on(robot, path.back())) return protocol::CodecStatus::ok();
    start_order(robot, position, path, now.wall_ns);
  } else if (!goes_on_to_base_end(robot, path[0])) {
    extend_order(robot, path);
  } else {
    changed = false;  // the order stands as sent; resend() sends it again until the robot takes it
  }
  if (changed) {
    if (auto s = send_order(robot, now, false, out.messages[0]); !s) return s;
    out.count = 1;
  }
  if (resume) {
    // The hold is over: on along the order, as it stands or extended.
    robot.holding = false;
    send_action(robot, "stopPause", now, out.messages[out.count++]);
  }
  return protocol::CodecStatus::ok();
}

bool VdaOrders::goes_on_to_base_end(const Robot& robot, Point waypoint) const {
  return !robot.order.order_id.empty() &&
         distance(waypoint, robot.order.nodes[robot.base_end].position) <= config_.same_node_m;
}

bool VdaOrders::is_halt(const Robot& robot, Point position, Point point) const {
  const double to_point = distance(point, position);
  // The node it drives to is its destination, however a correction moved it by millimetres (the
  // last leg is a one-point path too; held there, it would be held for good).
  if (to_point > config_.halt_radius_m || goes_on_to_base_end(robot, point)) return false;
  // The next waypoint once the robot is (nearly) at its node is a destination, not a halt.
  return robot.order.order_id.empty() ||
         to_point < distance(robot.order.nodes[robot.base_end].position, position);
}

void VdaOrders::send_action(Robot& robot, std::string_view action_type, const Instant& now,
                            OutboundMessage& out) {
  robot.unconfirmed = Robot::UnconfirmedAction{
      {fmt::format("{}-{}-{}", action_type, now.wall_ns / 1'000'000, ++robot.actions),
       std::string(action_type)},
      1,
      due_after(now, 1)};
  encode_action(robot, robot.unconfirmed->action, now.wall_ns, out);
}

std::int64_t VdaOrders::due_after(const Instant& now, std::size_t sends) const {
  return now.mono_ns + (static_cast<std::int64_t>(config_.resend_s * 1e9) << (sends - 1));
}

void VdaOrders::encode_action(Robot& robot, const protocol::VdaInstantAction& action, std::int64_t wall_ns,
                              OutboundMessage& out) {
  protocol::vda_topic(tree_, robot.manufacturer, robot.serial_number, protocol::VdaTopic::InstantActions,
                      out.topic);
  protocol::encode_vda_instant_actions(
      {robot.action_headers++, wall_ns, robot.manufacturer, robot.serial_number}, std::span(&action, 1),
      out.payload);
}

void VdaOrders::resend(const Instant& now, std::vector<OutboundMessage>& out,
                       std::vector<std::string>& given_up) {
  out.clear();
  given_up.clear();
  for (auto& [id, robot] : robots_) {
    resend_action(id, robot, now, out, given_up);
    resend_order(id, robot, now, out, given_up);
  }
}

void VdaOrders::resend_action(std::string_view id, Robot& robot, const Instant& now,
                              std::vector<OutboundMessage>& out, std::vector<std::string>& given_up) {
  if (!robot.unconfirmed || now.mono_ns < robot.unconfirmed->due_ns) return;
  Robot::UnconfirmedAction& a = *robot.unconfirmed;
  if (a.sends >= config_.max_sends) {
    given_up.push_back(
        fmt::format("robot '{}': instant action {} ({}) not in its state after {} sends, given up", id,
                    a.action.action_type, a.action.action_id, a.sends));
    robot.unconfirmed.reset();
    return;
  }
  encode_action(robot, a.action, now.wall_ns, out.emplace_back());
  a.due_ns = due_after(now, ++a.sends);
}

void VdaOrders::resend_order(std::string_view id, Robot& robot, const Instant& now,
                             std::vector<OutboundMessage>& out, std::vector<std::string>& given_up) {
  if (robot.order.order_id.empty() || robot.order_taken || robot.cancelling ||
      now.mono_ns < robot.order_due_ns)
    return;
  if (robot.order_sends >= config_.max_sends) {
    const VdaRejection r =
        reject(robot, fmt::format("not taken after {} sends, given up", robot.order_sends));
    given_up.push_back(fmt::format("robot '{}' {}", id, r.text));
    robot.order = {};  // the next path starts a new order, unless gave_up_on its destination
    return;
  }
  if (!send_order(robot, now, true, out.emplace_back())) out.pop_back();
}

void VdaOrders::cancel(Robot& robot, const Instant& now, OutboundMessage& out) {
  robot.cancelling = true;
  send_action(robot, "cancelOrder", now, out);
}

protocol::CodecStatus VdaOrders::send_order(Robot& robot, const Instant& now, bool again,
                                            OutboundMessage& out) {
  protocol::vda_topic(tree_, robot.manufacturer, robot.serial_number, protocol::VdaTopic::Order, out.topic);
  if (auto s = protocol::encode_vda_order(
          {robot.order_headers, now.wall_ns, robot.manufacturer, robot.serial_number}, robot.order, limits_,
          out.payload);
      !s) {
    robot.order = {};
    return s;
  }
  ++robot.order_headers;
  robot.order_taken = false;
  robot.order_sends = again ? robot.order_sends + 1 : 1;
  robot.order_due_ns = due_after(now, robot.order_sends);
  return protocol::CodecStatus::ok();
}

void VdaOrders::start_order(Robot& robot, std::optional<Point> position, std::span<const Point> path,
                            std::int64_t wall_ns) {
  protocol::VdaOrder& order = robot.order;
  // Unique across gateway restarts (clock) and within a millisecond (count): a robot ignores an
  // order whose id and update id it has seen.
  order.order_id = fmt::format("slam-{}-{}", wall_ns / 1'000'000, ++orders_started_);
  order.order_update_id = 0;
  order.map_id = robot.map_id;
  order.nodes.clear();
  // The standard has a new order begin where the robot stands.
  if (position && distance(*position, path[0]) > config_.same_node_m)
    order.nodes.push_back({node_id(0), 0, true, *position});
  append_route(order, path);
  robot.base_end = order.nodes.size() - path.size();
}

void VdaOrders::extend_order(Robot& robot, std::span<const Point> path) {
  protocol::VdaOrder& order = robot.order;
  protocol::VdaNode stitch = std::move(order.nodes[robot.base_end]);
  order.nodes.clear();
  order.nodes.push_back(std::move(stitch));
  ++order.order_update_id;
  append_route(order, path);
  robot.base_end = 1;
}

void VdaOrders::append_route(protocol::VdaOrder& order, std::span<const Point> path) {
  std::uint32_t sequence_id = order.nodes.empty() ? 0 : order.nodes.back().sequence_id + 2;
  for (std::size_t i = 0; i < path.size(); ++i, sequence_id += 2)
    order.nodes.push_back({node_id(sequence_id), sequence_id, i == 0, path[i]});
}

}  // namespace slam::gateway
