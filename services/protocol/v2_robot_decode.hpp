#pragma once
// v2 robot -> server messages (JSON, see docs/protocol.md), decoded into the same structs as v1.
// Every decoder clears its output first (capacity kept) and, on rejection, leaves nothing
// meaningful in it. Unknown JSON members are ignored so robots can add fields ahead of servers.
// pose, points and scan may carry "stamp": when the robot measured, in seconds on its own clock
// (finite, >= 0; robot_stamp_ns), rejected as json_type, non_finite or out_of_range otherwise.
#include <cstdint>
#include <span>

#include "protocol/codec_types.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::protocol {

// v2/robot/<id>/pose: {"x": 1.5, "y": -2.0, "heading": 0.3}; heading optional.
// Output: has_pose, has_heading when heading given, no points.
CodecStatus decode_v2_pose(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                           DecodedObservation& out);

// v2/robot/<id>/points: {"pose": {...}, "points": [[x, y], ...]}; pose optional (without it the
// service uses the robot's last known pose), points are map-frame obstacle hits.
CodecStatus decode_v2_points(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                             DecodedObservation& out);

// v2/robot/<id>/scan: polar beams relative to the robot, converted to map-frame hits and misses.
//   {"pose": {"x","y","heading"}, "sensor": {"x","y","theta"}, "max_range": 4.0,
//    "angle_min": -1.57, "angle_increment": 0.0175 | "angles": [...], "ranges": [1.2, null, ...]}
// pose (with heading), max_range and ranges are required; sensor defaults to the robot centre.
// A range >= max_range or null is a miss at max_range. Output pose is the sensor origin.
CodecStatus decode_v2_scan(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                           DecodedObservation& out);

// v2/robot/<id>/status: {"battery": 0.8, "state": "exploring"}; battery (0..1) optional.
// The last will is {"state": "offline"}, which sets `offline`.
CodecStatus decode_v2_status(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                             DecodedStatus& out);

}  // namespace slam::protocol
