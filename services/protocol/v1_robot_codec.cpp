// v1 waypoint decoding: a strict length check, since a legacy robot has no way to say "bad command".
#include "protocol/v1_robot_codec.hpp"

#include <fmt/format.h>

#include <cmath>

#include "protocol/v1_codec.hpp"

namespace slam::protocol {
namespace {

double int16_le(const std::uint8_t* p) {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(p[0] | (p[1] << 8)));
}

}  // namespace

CodecStatus decode_v1_waypoint(std::span<const std::uint8_t> payload, const CodecLimits& limits, Point& out) {
  if (payload.empty()) return {RejectReason::EmptyPayload, "v1 waypoint is empty, expected 4 bytes"};
  if (payload.size() != kV1PairBytes)
    return {RejectReason::BadLength,
            fmt::format("v1 waypoint is {} bytes, expected exactly 4", payload.size())};
  if (!std::isfinite(limits.units_per_meter))
    return {RejectReason::NonFinite, fmt::format("units_per_meter is {}", limits.units_per_meter)};
  if (limits.units_per_meter <= 0.0)
    return {RejectReason::OutOfRange,
            fmt::format("units_per_meter is {}, must be > 0", limits.units_per_meter)};
  out = Point{int16_le(payload.data()) / limits.units_per_meter,
              int16_le(payload.data() + 2) / limits.units_per_meter};
  return CodecStatus::ok();
}

}  // namespace slam::protocol
