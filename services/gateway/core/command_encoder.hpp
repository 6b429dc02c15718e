#pragma once
// A waypoint command from the planner (map frame), turned into what the robot understands: first
// into the robot's odometry frame with its correction, then into the protocol it spoke last: v1
// gets exactly one 4-byte int16 pair on v1/server/<id>/cmd (never wrapped: out of range is an
// error), v2 gets the waypoint JSON and the whole remaining path JSON, a VDA 5050 robot an order or
// instant actions (startPause, stopPause, cancelOrder) from VdaOrders.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/core/geometry.hpp"
#include "gateway/core/robot_registry.hpp"
#include "protocol/codec_types.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::gateway {

class VdaOrders;

struct OutboundMessage {
  std::string topic;
  std::string payload;  // bytes (binary for v1)
};

// The MQTT messages for one command; buffers keep their capacity between commands.
struct CommandMessages {
  std::array<OutboundMessage, 2> messages;
  std::size_t count = 0;
  std::span<const OutboundMessage> view() const { return {messages.data(), count}; }
};

class CommandEncoder {
 public:
  explicit CommandEncoder(const protocol::CodecLimits& limits) : limits_(limits) {}

  // Encodes the command for `robot_id` speaking `protocol`, whose odometry frame is placed in the
  // map by `map_from_odom`. `waypoint` and `remaining` (the rest of the path) are in the map frame;
  // whether or not `remaining` starts with `waypoint`, the v2 path sent starts with it exactly once.
  // On error (bad id, non-finite or out-of-range waypoint, too many points) out.count is 0.
  protocol::CodecStatus encode(std::string_view robot_id, Protocol protocol, std::uint64_t seq,
                               const Pose& map_from_odom, protocol::Point waypoint,
                               std::span<const protocol::Point> remaining, CommandMessages& out);
  // The same for a VDA 5050 robot standing at `odom_position` (its own frame, when known): the path,
  // converted alike, goes to `orders`, which keeps each robot's order.
  protocol::CodecStatus encode_vda(VdaOrders& orders, std::string_view robot_id, const Pose& map_from_odom,
                                   protocol::Point waypoint, std::span<const protocol::Point> remaining,
                                   std::optional<protocol::Point> odom_position, const Instant& now,
                                   CommandMessages& out);

 private:
  // path_ = the waypoint, then (`with_rest`) the rest without a repeated waypoint, in the odometry frame.
  void robot_path(const Pose& map_from_odom, protocol::Point waypoint,
                  std::span<const protocol::Point> remaining, bool with_rest);

  protocol::CodecLimits limits_;
  std::vector<protocol::Point> path_;  // waypoint then the rest, in the odometry frame
};

}  // namespace slam::gateway
