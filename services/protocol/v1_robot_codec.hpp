#pragma once
// The robot's half of v1 (what a 2019 robot, or the simulator, decodes): the server's waypoint
// command on v1/server/<id>/cmd, exactly one little-endian int16 (x, y) pair in robot units.
#include <cstdint>
#include <span>

#include "protocol/codec_types.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::protocol {

// Decodes a 4-byte v1 waypoint into metres (value / limits.units_per_meter). EmptyPayload for no
// bytes, BadLength for any length but 4, NonFinite/OutOfRange for a bad units_per_meter. `out` is
// written only on success, so a robot keeps its last valid goal on a bad command.
CodecStatus decode_v1_waypoint(std::span<const std::uint8_t> payload, const CodecLimits& limits, Point& out);

}  // namespace slam::protocol
