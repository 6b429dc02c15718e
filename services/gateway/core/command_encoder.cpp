// CommandEncoder: one frame conversion for every protocol, then topics and payloads per protocol,
// with every codec error passed through.
#include "gateway/core/command_encoder.hpp"

#include "gateway/core/frame_correction.hpp"
#include "gateway/core/vda_orders.hpp"
#include "protocol/topic.hpp"
#include "protocol/v1_codec.hpp"
#include "protocol/v2_server_codec.hpp"

namespace slam::gateway {

void CommandEncoder::robot_path(const Pose& map_from_odom, protocol::Point waypoint,
                                std::span<const protocol::Point> remaining, bool with_rest) {
  // Planners differ on whether "remaining" includes the current waypoint; robots get it once.
  // (Compared in the map frame, where the planner made them equal.)
  path_.assign(1, waypoint);
  if (with_rest) {
    const bool repeats = !remaining.empty() && remaining.front() == waypoint;
    path_.insert(path_.end(), remaining.begin() + (repeats ? 1 : 0), remaining.end());
  }
  to_odometry_frame(map_from_odom, path_);
}

protocol::CodecStatus CommandEncoder::encode_vda(VdaOrders& orders, std::string_view robot_id,
                                                 const Pose& map_from_odom, protocol::Point waypoint,
                                                 std::span<const protocol::Point> remaining,
                                                 std::optional<protocol::Point> odom_position,
                                                 const Instant& now, CommandMessages& out) {
  robot_path(map_from_odom, waypoint, remaining, true);
  return orders.command(robot_id, odom_position, path_, now, out);
}

protocol::CodecStatus CommandEncoder::encode(std::string_view robot_id, Protocol protocol, std::uint64_t seq,
                                             const Pose& map_from_odom, protocol::Point waypoint,
                                             std::span<const protocol::Point> remaining,
                                             CommandMessages& out) {
  out.count = 0;
  // v1 robots take the waypoint only.
  robot_path(map_from_odom, waypoint, remaining, protocol != Protocol::V1);
  const protocol::Point target = path_.front();

  if (protocol == Protocol::V1) {
    OutboundMessage& m = out.messages[0];
    if (auto s = protocol::v1_command_topic(robot_id, m.topic); !s) return s;
    std::array<std::uint8_t, protocol::kV1PairBytes> bytes{};
    if (auto s = protocol::encode_v1_waypoint(target, limits_.units_per_meter, bytes); !s) return s;
    m.payload.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    out.count = 1;
    return protocol::CodecStatus::ok();
  }

  OutboundMessage& w = out.messages[0];
  OutboundMessage& p = out.messages[1];
  if (auto s = protocol::v2_waypoint_topic(robot_id, w.topic); !s) return s;
  if (auto s = protocol::v2_path_topic(robot_id, p.topic); !s) return s;
  if (auto s = protocol::encode_v2_waypoint({seq, target}, limits_, w.payload); !s) return s;
  if (auto s = protocol::encode_v2_path(seq, path_, limits_, p.payload); !s) return s;
  out.count = 2;
  return protocol::CodecStatus::ok();
}

}  // namespace slam::gateway
