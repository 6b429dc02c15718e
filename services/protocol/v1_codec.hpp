#pragma once
// The 2019 robots' binary protocol, byte-compatible: little-endian int16 (x, y) pairs in robot
// units. Robot -> server: pair 0 is the position, pairs 1..k-1 obstacle points. Server -> robot:
// exactly one pair, the next waypoint. Values never wrap: out of int16 range is an error.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "protocol/codec_types.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::protocol {

inline constexpr std::size_t kV1PairBytes = 4;

// Decodes a v1 adv payload into `out` (cleared first, capacity kept). Rejects: EmptyPayload,
// Oversized, BadLength (size % 4 != 0), TooManyPoints (k - 1 > max_points), NonFinite/OutOfRange
// (bad units_per_meter or a coordinate beyond max_abs_coordinate_m). On success: has_pose, no
// heading, hits = obstacle points, no misses. On rejection `out` holds nothing meaningful.
CodecStatus decode_v1(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                      DecodedObservation& out);

// Metres -> one int16 LE pair (rounded to nearest, halves away from zero). NonFinite for NaN/inf
// input or units_per_meter, OutOfRange when a value leaves [-32768, 32767] robot units.
CodecStatus encode_v1_waypoint(Point waypoint, double units_per_meter,
                               std::array<std::uint8_t, kV1PairBytes>& out);

// A robot's adv message (position then obstacles), as a v1 robot or the simulator sends it.
// `out` is replaced, capacity kept; empty on error. Same errors as encode_v1_waypoint.
CodecStatus encode_v1_adv(Point position, std::span<const Point> obstacles, double units_per_meter,
                          std::vector<std::uint8_t>& out);

}  // namespace slam::protocol
