// v1 binary codec. Decoding is the gateway's hottest path: no allocation once `out` has grown.
#include "protocol/v1_codec.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <string>

namespace slam::protocol {
namespace {

double read_int16_le(const std::uint8_t* p) {
  // C++20 defines the uint16 -> int16 conversion as two's complement.
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(p[0] | (p[1] << 8)));
}

CodecStatus check_units(double units_per_meter) {
  if (!std::isfinite(units_per_meter))
    return {RejectReason::NonFinite, fmt::format("units_per_meter is {}", units_per_meter)};
  if (units_per_meter <= 0.0)
    return {RejectReason::OutOfRange, fmt::format("units_per_meter is {}, must be > 0", units_per_meter)};
  return CodecStatus::ok();
}

CodecStatus to_robot_units(double metres, double units_per_meter, const char* what, std::uint8_t* out) {
  if (!std::isfinite(metres)) return {RejectReason::NonFinite, fmt::format("{} is {}", what, metres)};
  const double units = std::round(metres * units_per_meter);
  constexpr double kMin = std::numeric_limits<std::int16_t>::min();
  constexpr double kMax = std::numeric_limits<std::int16_t>::max();
  if (!(units >= kMin && units <= kMax))
    return {RejectReason::OutOfRange, fmt::format("{} = {} m is {} robot units, outside int16 [{}, {}]", what,
                                                  metres, units, kMin, kMax)};
  const auto bits = static_cast<std::uint16_t>(static_cast<std::int16_t>(units));
  out[0] = static_cast<std::uint8_t>(bits & 0xFF);
  out[1] = static_cast<std::uint8_t>(bits >> 8);
  return CodecStatus::ok();
}

CodecStatus encode_pair(Point p, double units_per_meter, const char* x_name, const char* y_name,
                        std::uint8_t* out) {
  if (auto status = to_robot_units(p.x, units_per_meter, x_name, out); !status) return status;
  return to_robot_units(p.y, units_per_meter, y_name, out + 2);
}

}  // namespace

CodecStatus decode_v1(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                      DecodedObservation& out) {
  out.clear();
  if (payload.empty())
    return {RejectReason::EmptyPayload, "v1 payload is empty, expected at least one int16 pair"};
  if (payload.size() > limits.max_payload_bytes)
    return {RejectReason::Oversized,
            fmt::format("payload is {} bytes, limit {}", payload.size(), limits.max_payload_bytes)};
  if (payload.size() % kV1PairBytes != 0)
    return {RejectReason::BadLength, fmt::format("payload is {} bytes, not a multiple of 4", payload.size())};
  const std::size_t obstacles = payload.size() / kV1PairBytes - 1;
  if (obstacles > limits.max_points)
    return {RejectReason::TooManyPoints,
            fmt::format("{} obstacle points, limit {}", obstacles, limits.max_points)};
  if (auto status = check_units(limits.units_per_meter); !status) return status;

  const double scale = 1.0 / limits.units_per_meter;
  const double bound = limits.max_abs_coordinate_m;
  // With sane settings no int16 exceeds the bound; checking the extreme once keeps the loop lean.
  if (32768.0 * scale > bound) {
    for (std::size_t i = 0; i < payload.size(); i += 2) {
      const double metres = read_int16_le(&payload[i]) * scale;
      if (std::abs(metres) > bound)
        return {RejectReason::OutOfRange, fmt::format("pair {} has {} m, beyond max_abs_coordinate_m {}",
                                                      i / kV1PairBytes, metres, bound)};
    }
  }
  const std::uint8_t* p = payload.data();
  out.x = read_int16_le(p) * scale;
  out.y = read_int16_le(p + 2) * scale;
  out.has_pose = true;
  out.hits.resize(obstacles);
  for (std::size_t i = 0; i < obstacles; ++i) {
    const std::uint8_t* q = p + (i + 1) * kV1PairBytes;
    out.hits[i] = Point{read_int16_le(q) * scale, read_int16_le(q + 2) * scale};
  }
  return CodecStatus::ok();
}

CodecStatus encode_v1_waypoint(Point waypoint, double units_per_meter,
                               std::array<std::uint8_t, kV1PairBytes>& out) {
  if (auto status = check_units(units_per_meter); !status) return status;
  std::array<std::uint8_t, kV1PairBytes> bytes{};
  if (auto status = encode_pair(waypoint, units_per_meter, "waypoint x", "waypoint y", bytes.data()); !status)
    return status;
  out = bytes;
  return CodecStatus::ok();
}

CodecStatus encode_v1_adv(Point position, std::span<const Point> obstacles, double units_per_meter,
                          std::vector<std::uint8_t>& out) {
  out.clear();
  if (auto status = check_units(units_per_meter); !status) return status;
  out.resize((obstacles.size() + 1) * kV1PairBytes);
  auto status = encode_pair(position, units_per_meter, "position x", "position y", out.data());
  for (std::size_t i = 0; status && i < obstacles.size(); ++i) {
    status = encode_pair(obstacles[i], units_per_meter, "x", "y", out.data() + (i + 1) * kV1PairBytes);
    if (!status) status = {status.reason(), fmt::format("obstacle {}: {}", i, status.detail())};
  }
  if (!status) out.clear();
  return status;
}

}  // namespace slam::protocol
