#pragma once
// What the VDA 5050 fleet control's side (vda5050_codec.cpp) and the robot's side
// (vda5050_robot_codec.cpp) share. Internal to robot_protocol.
#include <cstddef>
#include <cstdint>
#include <string>

#include "protocol/json_fields.hpp"
#include "protocol/vda5050_codec.hpp"

namespace slam::protocol::vda5050_fields {

// Ids and names a robot sends (orderId, mapId, nodeId, ...): bounded so a robot cannot grow the
// gateway's memory through them. Free-text descriptions are cut to it instead of rejected.
inline constexpr std::size_t kMaxTextBytes = 256;

// headerId, timestamp, version, manufacturer and serialNumber.
void append_header(json_fields::Json& doc, const VdaHeader& header);

// orderId and orderUpdateId: which order, and which update of it (an order, a robot's state).
CodecStatus read_order_identity(const json_fields::Json& doc, std::string& order_id,
                                std::uint32_t& order_update_id);

}  // namespace slam::protocol::vda5050_fields
