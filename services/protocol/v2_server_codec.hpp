#pragma once
// v2 server -> robot messages (JSON): the next waypoint and the whole path. Encoded by the gateway,
// decoded by v2 robots (the simulator among them). Numbers are written in the shortest form that
// reads back to the same double, so encode -> decode is exact.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "protocol/codec_types.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::protocol {

// v2/server/<id>/waypoint: {"seq":7,"x":1.5,"y":-2}
struct V2Waypoint {
  std::uint64_t seq = 0;
  Point waypoint;
};

// v2/server/<id>/path: {"seq":7,"points":[[1.5,-2],[3,0.25]]}; empty points: nothing to drive to.
struct V2Path {
  std::uint64_t seq = 0;
  std::vector<Point> points;
  void clear() {
    seq = 0;
    points.clear();
  }
};

// `out` is replaced (capacity kept); empty on error. NonFinite for NaN/inf, OutOfRange beyond
// limits.max_abs_coordinate_m, TooManyPoints beyond limits.max_points.
CodecStatus encode_v2_waypoint(const V2Waypoint& message, const CodecLimits& limits, std::string& out);
CodecStatus encode_v2_path(std::uint64_t seq, std::span<const Point> points, const CodecLimits& limits,
                           std::string& out);

// Robot-side decoders with the same checks as the robot -> server ones; seq must be an unsigned
// integer (JsonType otherwise).
CodecStatus decode_v2_waypoint(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                               V2Waypoint& out);
CodecStatus decode_v2_path(std::span<const std::uint8_t> payload, const CodecLimits& limits, V2Path& out);

}  // namespace slam::protocol
