// v2 waypoint and path messages. Encoding writes JSON text directly (no document, no allocation
// once `out` has grown): waypoints are re-sent every second to every robot with a target.
#include "protocol/v2_server_codec.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "protocol/json_fields.hpp"

namespace slam::protocol {
namespace {

using json_fields::FieldName;
using json_fields::Json;

CodecStatus check_point(Point p, const FieldName& name, const CodecLimits& limits) {
  const double bound = limits.max_abs_coordinate_m;
  for (const double v : {p.x, p.y}) {
    if (!std::isfinite(v)) return {RejectReason::NonFinite, fmt::format("{} has {}", name.str(), v)};
    if (std::abs(v) > bound)
      return {RejectReason::OutOfRange, fmt::format("{} has {}, limit +/-{}", name.str(), v, bound)};
  }
  return CodecStatus::ok();
}

template <class T>
void append_number(std::string& out, T value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);  // shortest round-trip form
  out.append(buffer, result.ptr);
}

void append_pair(std::string& out, Point p) {
  out += '[';
  append_number(out, p.x);
  out += ',';
  append_number(out, p.y);
  out += ']';
}

CodecStatus read_seq(const Json& doc, std::uint64_t& out) {
  const Json* seq = nullptr;
  if (auto s = json_fields::require(doc, "seq", {"seq"}, seq); !s) return s;
  if (!seq->is_number_unsigned())
    return {RejectReason::JsonType, fmt::format("seq is {}, expected an unsigned integer", seq->type_name())};
  out = seq->get<std::uint64_t>();
  return CodecStatus::ok();
}

}  // namespace

CodecStatus encode_v2_waypoint(const V2Waypoint& message, const CodecLimits& limits, std::string& out) {
  out.clear();
  if (auto s = check_point(message.waypoint, {"waypoint"}, limits); !s) return s;
  out += "{\"seq\":";
  append_number(out, message.seq);
  out += ",\"x\":";
  append_number(out, message.waypoint.x);
  out += ",\"y\":";
  append_number(out, message.waypoint.y);
  out += '}';
  return CodecStatus::ok();
}

CodecStatus encode_v2_path(std::uint64_t seq, std::span<const Point> points, const CodecLimits& limits,
                           std::string& out) {
  out.clear();
  if (points.size() > limits.max_points)
    return {RejectReason::TooManyPoints,
            fmt::format("path has {} points, limit {}", points.size(), limits.max_points)};
  for (std::size_t i = 0; i < points.size(); ++i)
    if (auto s = check_point(points[i], {"points", i}, limits); !s) return s;
  out += "{\"seq\":";
  append_number(out, seq);
  out += ",\"points\":[";
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i > 0) out += ',';
    append_pair(out, points[i]);
  }
  out += "]}";
  return CodecStatus::ok();
}

CodecStatus decode_v2_waypoint(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                               V2Waypoint& out) {
  out = V2Waypoint{};
  Json doc;
  if (auto s = json_fields::parse_object(payload, limits, doc); !s) return s;
  if (auto s = read_seq(doc, out.seq); !s) return s;
  const double bound = limits.max_abs_coordinate_m;
  if (auto s = json_fields::member_number(doc, "x", {"x"}, bound, out.waypoint.x); !s) return s;
  return json_fields::member_number(doc, "y", {"y"}, bound, out.waypoint.y);
}

CodecStatus decode_v2_path(std::span<const std::uint8_t> payload, const CodecLimits& limits, V2Path& out) {
  out.clear();
  Json doc;
  if (auto s = json_fields::parse_object(payload, limits, doc); !s) return s;
  if (auto s = read_seq(doc, out.seq); !s) return s;
  const Json* points = nullptr;
  if (auto s = json_fields::require(doc, "points", {"points"}, points); !s) return s;
  if (auto s = json_fields::expect_array(*points, {"points"}); !s) return s;
  if (points->size() > limits.max_points)
    return {RejectReason::TooManyPoints,
            fmt::format("points has {} entries, limit {}", points->size(), limits.max_points)};
  out.points.resize(points->size());
  for (std::size_t i = 0; i < points->size(); ++i)
    if (auto s = json_fields::point_pair((*points)[i], {"points", i}, limits, out.points[i]); !s) return s;
  return CodecStatus::ok();
}

}  // namespace slam::protocol
