#pragma once
// The fleet control's side of each VDA 5050 robot: its address (manufacturer, serialNumber) and map,
// the header ids it has been sent per topic, and the order it drives. The planner streams a waypoint
// and the rest of the path, as for v1/v2 robots; here that becomes an order whose base (released
// nodes) ends at the waypoint and whose horizon is the rest, so the robot drives only as far as the
// planner (and its traffic rules) released. When the planner moves the waypoint on, the order is
// extended by an update stitched at the last base node. A halt (a stop goal or a traffic hold: a
// one-point path where the robot is, while it drives towards a node further away; the planner sends
// both alike) pauses the robot with the instant action startPause and keeps the order; the next path
// resumes it with stopPause when it goes on to the same node (the hold is over), else cancels the
// order with cancelOrder, and a new order (with stopPause if the robot is still paused) follows once
// the robot's state shows the cancel done. Plain and single-threaded: the gateway's loop owns it.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "gateway/core/command_encoder.hpp"
#include "protocol/codec_types.hpp"
#include "protocol/reject_reason.hpp"
#include "protocol/vda5050_codec.hpp"

namespace slam::gateway {

struct VdaOrdersConfig {
  // Path points this close are the same node: the planner re-sends its waypoint every second, and a
  // correction update moves it by millimetres in the robot's frame.
  double same_node_m = 0.05;
  // A one-point path within this of a driving robot, nearer than the node it drives to, is a halt,
  // not a destination: the planner's stop and traffic holds are the robot's own position as it last
  // saw it. The standard's default deviation is 0.5 m.
  double halt_radius_m = 0.5;
  // An order (update) or instant action is sent again until the robot's state shows it taken (QoS 0
  // may lose it): after this long, then twice as long each time, max_sends times in all; then it is
  // given up (an order as if rejected).
  double resend_s = 1.0;
  std::size_t max_sends = 4;
  // Orders rejected in a row for one destination before none is sent there any more (until the
  // planner's path ends elsewhere): a robot that cannot take it would be sent it every second.
  std::size_t max_rejections = 3;
  std::size_t max_robots = 10'000;
};

// An order (update) the robot rejected: the line saying so, with the robot's error, and whether no
// order goes to its destination any more (VdaOrdersConfig::max_rejections).
struct VdaRejection {
  std::string text;
  bool gave_up = false;
};

class VdaOrders {
 public:
  VdaOrders(protocol::VdaTree tree, protocol::CodecLimits limits, VdaOrdersConfig config = {});

  // A valid message from robot `id` at `address`: learns its address and map; a state also says
  // what became of the order sent last. Returns the robot's reason when that order (its current
  // update) was rejected, once per update. False in `known` when the robot is new and max_robots
  // are known already.
  std::optional<VdaRejection> take_message(std::string_view id, const protocol::VdaAddress& address,
                                           const protocol::VdaMessage& message, bool& known);
  bool knows(std::string_view id) const { return robots_.contains(id); }
  void forget(std::string_view id);

  // The orders and instant actions due to be sent again at `now` into `out` (cleared first), and a
  // line for each one given up (its robot, what, how often it was sent) into `given_up` (cleared first).
  void resend(const Instant& now, std::vector<OutboundMessage>& out, std::vector<std::string>& given_up);

  // The messages that put the robot, standing at `position`, onto `path` (path[0] the waypoint to
  // drive to now, the rest of the route after it; everything in the robot's map). Nothing to send
  // (out.count 0) while a cancel is under way, to a robot held already, for an empty path or to a
  // destination the robot rejected max_rejections orders to in a row; two
  // messages (the order, then stopPause) when a hold ends. UnknownRobot when no message from the
  // robot was seen; codec errors for a node that cannot be encoded.
  protocol::CodecStatus command(std::string_view id, std::optional<protocol::Point> position,
                                std::span<const protocol::Point> path, const Instant& now,
                                CommandMessages& out);

 private:
  struct Robot {
    std::string manufacturer;
    std::string serial_number;
    std::string map_id;
    std::uint32_t order_headers = 0;   // headerId of the next order
    std::uint32_t action_headers = 0;  // headerId of the next instantActions
    std::uint64_t actions = 0;         // instant actions sent: their ids
    protocol::VdaOrder order;          // the one sent last; order_id empty: none
    std::size_t base_end = 0;          // its last released node
    bool order_taken = false;          // a state has shown its orderId and orderUpdateId
    std::size_t order_sends = 0;       // of its current update
    std::int64_t order_due_ns = 0;     // monotonic: when it is sent again, unless taken
    bool cancelling = false;           // cancelOrder sent, the robot's state has not shown it done
    bool holding = false;              // startPause sent, no stopPause since: the robot is held
    // The instant action sent last, until the robot's state lists it (a newer one replaces it).
    struct UnconfirmedAction {
      protocol::VdaInstantAction action;
      std::size_t sends = 1;
      std::int64_t due_ns = 0;  // monotonic: when it is sent again
    };
    std::optional<UnconfirmedAction> unconfirmed;
    // From its latest state.
    bool has_state = false;
    bool busy = false;  // node or edge states left: an order (ours or not) is under way
    bool driving = false;
    std::string robot_order_id;
    std::string rejection_reported;  // "<orderId>/<orderUpdateId>" whose rejection was reported
    std::size_t rejections = 0;      // orders rejected in a row, all to rejected_destination
    protocol::Point rejected_destination;
  };
  struct Hash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };

  void take_state(Robot& robot, const protocol::VdaMessage& state, std::optional<VdaRejection>& rejection);
  // Counts a rejection of the robot's order (in a row when to the same destination as the last one)
  // and says it, with `reason`.
  VdaRejection reject(Robot& robot, const std::string& reason);
  // Has the robot rejected max_rejections orders to `destination` in a row (then no new one is sent)?
  bool gave_up_on(const Robot& robot, protocol::Point destination) const;
  // Is `waypoint` the last released node of the robot's order (the planner's waypoint unchanged)?
  bool goes_on_to_base_end(const Robot& robot, protocol::Point waypoint) const;
  // A one-point path to `point`, for a robot driving at `position`: a halt (see VdaOrdersConfig)?
  bool is_halt(const Robot& robot, protocol::Point position, protocol::Point point) const;
  // One instantActions message with the action `action_type`, under an id of its own.
  void send_action(Robot& robot, std::string_view action_type, const Instant& now, OutboundMessage& out);
  void encode_action(Robot& robot, const protocol::VdaInstantAction& action, std::int64_t wall_ns,
                     OutboundMessage& out);
  // cancelOrder: nothing more is sent until the state shows it done.
  void cancel(Robot& robot, const Instant& now, OutboundMessage& out);
  // Encodes robot.order as it stands into `out`, a new update (first send) or `again`.
  protocol::CodecStatus send_order(Robot& robot, const Instant& now, bool again, OutboundMessage& out);
  // resend() of one robot's unconfirmed instant action, and of its order not taken yet.
  void resend_action(std::string_view id, Robot& robot, const Instant& now, std::vector<OutboundMessage>& out,
                     std::vector<std::string>& given_up);
  void resend_order(std::string_view id, Robot& robot, const Instant& now, std::vector<OutboundMessage>& out,
                    std::vector<std::string>& given_up);
  // When what was sent `sends` times at `now` is due again: the wait doubles with each send.
  std::int64_t due_after(const Instant& now, std::size_t sends) const;
  // A new order: from where the robot stands (when known and not at path[0]) along the path.
  void start_order(Robot& robot, std::optional<protocol::Point> position,
                   std::span<const protocol::Point> path, std::int64_t wall_ns);
  // The next update: from the last base node to path[0] released, the rest as horizon.
  void extend_order(Robot& robot, std::span<const protocol::Point> path);
  // Appends path[0] (released) and the rest (horizon) after the order's last node.
  static void append_route(protocol::VdaOrder& order, std::span<const protocol::Point> path);

  protocol::VdaTree tree_;
  protocol::CodecLimits limits_;
  VdaOrdersConfig config_;
  std::uint64_t orders_started_ = 0;
  std::unordered_map<std::string, Robot, Hash, std::equal_to<>> robots_;
};

}  // namespace slam::gateway
