// Decoders for the v2 robot messages: field shapes, bounds and the scan's polar-to-map transform.
#include "protocol/v2_robot_decode.hpp"

#include <fmt/format.h>

#include <cmath>

#include "protocol/json_fields.hpp"
#include "protocol/text_check.hpp"

namespace slam::protocol {
namespace {

using json_fields::FieldName;
using json_fields::Json;

// Reads {x, y, heading} from `object` into `out`. `where` prefixes field names in messages.
CodecStatus read_pose(const Json& object, std::string_view where, bool heading_required,
                      const CodecLimits& limits, DecodedObservation& out) {
  const double c = limits.max_abs_coordinate_m;
  if (auto s = json_fields::member_number(object, "x", {where, FieldName::kNoIndex, "x"}, c, out.x); !s)
    return s;
  if (auto s = json_fields::member_number(object, "y", {where, FieldName::kNoIndex, "y"}, c, out.y); !s)
    return s;
  out.has_pose = true;
  const FieldName heading_name{where, FieldName::kNoIndex, "heading"};
  const Json* heading =
      heading_required ? json_fields::find(object, "heading") : json_fields::find_optional(object, "heading");
  if (heading == nullptr) {
    if (heading_required)
      return {RejectReason::MissingField,
              fmt::format("{} is missing (a scan needs the heading)", heading_name.str())};
    return CodecStatus::ok();
  }
  if (auto s = json_fields::number(*heading, heading_name, limits.max_abs_angle_rad, out.theta); !s) return s;
  out.has_heading = true;
  return CodecStatus::ok();
}

// The nested "pose" object of points and scan messages.
CodecStatus read_nested_pose(const Json& doc, bool required, const CodecLimits& limits,
                             DecodedObservation& out) {
  const Json* pose = json_fields::find_optional(doc, "pose");
  if (pose == nullptr) {
    if (required) return {RejectReason::MissingField, "pose is missing"};
    return CodecStatus::ok();
  }
  if (auto s = json_fields::expect_object(*pose, {"pose"}); !s) return s;
  return read_pose(*pose, "pose", required, limits, out);
}

// The optional top-level "stamp": seconds on the robot's clock, finite and >= 0; absent or null
// leaves robot_stamp_ns at 0 (unknown).
CodecStatus read_stamp(const Json& doc, DecodedObservation& out) {
  const Json* stamp = json_fields::find_optional(doc, "stamp");
  if (stamp == nullptr) return CodecStatus::ok();
  double seconds = 0.0;
  if (auto s = json_fields::number(*stamp, {"stamp"}, kMaxRobotStampS, seconds); !s) return s;
  if (seconds < 0.0) return {RejectReason::OutOfRange, fmt::format("stamp is {}, must be >= 0", seconds)};
  out.robot_stamp_ns = static_cast<std::int64_t>(std::llround(seconds * 1e9));
  return CodecStatus::ok();
}

CodecStatus check_count(std::size_t count, std::string_view what, const CodecLimits& limits) {
  if (count <= limits.max_points) return CodecStatus::ok();
  return {RejectReason::TooManyPoints,
          fmt::format("{} has {} entries, limit {}", what, count, limits.max_points)};
}

struct SensorOffset {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
};

// Every member of "sensor" defaults to 0: most robots only need to state what differs.
CodecStatus read_sensor(const Json& doc, const CodecLimits& limits, SensorOffset& out) {
  const Json* sensor = json_fields::find_optional(doc, "sensor");
  if (sensor == nullptr) return CodecStatus::ok();
  if (auto s = json_fields::expect_object(*sensor, {"sensor"}); !s) return s;
  struct Member {
    std::string_view key;
    double bound;
    double* value;
  };
  const Member members[] = {{"x", limits.max_abs_coordinate_m, &out.x},
                            {"y", limits.max_abs_coordinate_m, &out.y},
                            {"theta", limits.max_abs_angle_rad, &out.theta}};
  for (const auto& m : members) {
    const Json* value = json_fields::find_optional(*sensor, m.key);
    if (value == nullptr) continue;
    if (auto s = json_fields::number(*value, {"sensor", FieldName::kNoIndex, m.key}, m.bound, *m.value); !s)
      return s;
  }
  return CodecStatus::ok();
}

// Beam angles are either explicit ("angles") or a start and a step; exactly one form.
struct BeamAngles {
  const Json* list = nullptr;
  double min = 0.0;
  double increment = 0.0;
};

CodecStatus read_angles(const Json& doc, std::size_t beams, const CodecLimits& limits, BeamAngles& out) {
  out.list = json_fields::find_optional(doc, "angles");
  const bool has_start = json_fields::find(doc, "angle_min") != nullptr;
  const bool has_step = json_fields::find(doc, "angle_increment") != nullptr;
  if (out.list != nullptr) {
    if (has_start || has_step)
      return {RejectReason::JsonType, "give either angles or angle_min + angle_increment, not both"};
    if (auto s = json_fields::expect_array(*out.list, {"angles"}); !s) return s;
    if (out.list->size() != beams)
      return {RejectReason::BadLength,
              fmt::format("angles has {} entries but ranges has {}", out.list->size(), beams)};
    return CodecStatus::ok();
  }
  if (!has_start && !has_step)
    return {RejectReason::MissingField, "angle_min and angle_increment (or angles) are missing"};
  const double a = limits.max_abs_angle_rad;
  if (auto s = json_fields::member_number(doc, "angle_min", {"angle_min"}, a, out.min); !s) return s;
  return json_fields::member_number(doc, "angle_increment", {"angle_increment"}, a, out.increment);
}

CodecStatus check_endpoint(Point p, std::size_t beam, const CodecLimits& limits) {
  const double bound = limits.max_abs_coordinate_m;
  if (std::abs(p.x) <= bound && std::abs(p.y) <= bound) return CodecStatus::ok();
  return {RejectReason::OutOfRange,
          fmt::format("beam {} ends at ({}, {}), beyond max_abs_coordinate_m {}", beam, p.x, p.y, bound)};
}

}  // namespace

CodecStatus decode_v2_pose(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                           DecodedObservation& out) {
  out.clear();
  Json doc;
  if (auto s = json_fields::parse_object(payload, limits, doc); !s) return s;
  if (auto s = read_stamp(doc, out); !s) return s;
  return read_pose(doc, "", false, limits, out);
}

CodecStatus decode_v2_points(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                             DecodedObservation& out) {
  out.clear();
  Json doc;
  if (auto s = json_fields::parse_object(payload, limits, doc); !s) return s;
  if (auto s = read_stamp(doc, out); !s) return s;
  if (auto s = read_nested_pose(doc, false, limits, out); !s) return s;
  const Json* points = nullptr;
  if (auto s = json_fields::require(doc, "points", {"points"}, points); !s) return s;
  if (auto s = json_fields::expect_array(*points, {"points"}); !s) return s;
  if (auto s = check_count(points->size(), "points", limits); !s) return s;
  out.hits.resize(points->size());
  for (std::size_t i = 0; i < points->size(); ++i)
    if (auto s = json_fields::point_pair((*points)[i], {"points", i}, limits, out.hits[i]); !s) return s;
  return CodecStatus::ok();
}

CodecStatus decode_v2_scan(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                           DecodedObservation& out) {
  out.clear();
  Json doc;
  if (auto s = json_fields::parse_object(payload, limits, doc); !s) return s;
  if (auto s = read_stamp(doc, out); !s) return s;
  if (auto s = read_nested_pose(doc, true, limits, out); !s) return s;
  SensorOffset sensor;
  if (auto s = read_sensor(doc, limits, sensor); !s) return s;
  double max_range = 0.0;
  if (auto s =
          json_fields::member_number(doc, "max_range", {"max_range"}, limits.max_abs_coordinate_m, max_range);
      !s)
    return s;
  if (max_range <= 0.0)
    return {RejectReason::OutOfRange, fmt::format("max_range is {}, must be > 0", max_range)};
  const Json* ranges = nullptr;
  if (auto s = json_fields::require(doc, "ranges", {"ranges"}, ranges); !s) return s;
  if (auto s = json_fields::expect_array(*ranges, {"ranges"}); !s) return s;
  if (auto s = check_count(ranges->size(), "ranges", limits); !s) return s;
  BeamAngles angles;
  if (auto s = read_angles(doc, ranges->size(), limits, angles); !s) return s;

  // The observation's pose becomes the sensor origin in the map frame (robot pose composed with
  // the mounting offset): that is where the mapper casts the rays from.
  const double c = std::cos(out.theta);
  const double sn = std::sin(out.theta);
  const double ox = out.x + c * sensor.x - sn * sensor.y;
  const double oy = out.y + sn * sensor.x + c * sensor.y;
  const double heading = out.theta + sensor.theta;
  const double bound = limits.max_abs_coordinate_m;
  if (std::abs(ox) > bound || std::abs(oy) > bound)
    return {RejectReason::OutOfRange,
            fmt::format("sensor origin ({}, {}) is beyond max_abs_coordinate_m {}", ox, oy, bound)};
  out.x = ox;
  out.y = oy;
  out.theta = heading;

  out.hits.reserve(ranges->size());
  out.misses.reserve(ranges->size());
  for (std::size_t i = 0; i < ranges->size(); ++i) {
    double angle = angles.min + static_cast<double>(i) * angles.increment;
    if (angles.list != nullptr) {
      if (auto s = json_fields::number((*angles.list)[i], {"angles", i}, limits.max_abs_angle_rad, angle); !s)
        return s;
    }
    const Json& r = (*ranges)[i];
    double range = max_range;
    bool hit = false;
    if (!r.is_null()) {
      if (auto s = json_fields::number(r, {"ranges", i}, limits.max_abs_coordinate_m, range); !s) return s;
      if (range < 0.0)
        return {RejectReason::OutOfRange, fmt::format("ranges[{}] is {}, must be >= 0", i, range)};
      if (range == 0.0) {
        ++out.error_beams;  // an error reading: not an obstacle at the sensor, not free space
        continue;
      }
      hit = range < max_range;
    }
    if (!hit) range = std::min(max_range, limits.scan_free_range_m);
    const double a = heading + angle;
    const Point end{ox + range * std::cos(a), oy + range * std::sin(a)};
    if (auto s = check_endpoint(end, i, limits); !s) return s;
    (hit ? out.hits : out.misses).push_back(end);
  }
  return CodecStatus::ok();
}

CodecStatus decode_v2_status(std::span<const std::uint8_t> payload, const CodecLimits& limits,
                             DecodedStatus& out) {
  out.clear();
  Json doc;
  if (auto s = json_fields::parse_object(payload, limits, doc); !s) return s;
  const Json* state = nullptr;
  if (auto s = json_fields::require(doc, "state", {"state"}, state); !s) return s;
  if (!state->is_string())
    return {RejectReason::JsonType, fmt::format("state is {}, expected a string", state->type_name())};
  const auto& text = state->get_ref<const std::string&>();
  if (text.empty()) return {RejectReason::BadText, "state is empty"};
  if (text.size() > kMaxStateBytes)
    return {RejectReason::BadText, fmt::format("state is {} bytes, limit {}", text.size(), kMaxStateBytes)};
  if (const auto problem = find_text_problem(text))
    return {RejectReason::BadText, fmt::format("state has {} at byte {}", problem->what, problem->offset)};
  if (const Json* battery = json_fields::find_optional(doc, "battery")) {
    double level = 0.0;
    if (auto s = json_fields::number(*battery, {"battery"}, 1.0, level); !s) return s;
    if (level < 0.0) return {RejectReason::OutOfRange, fmt::format("battery is {}, must be in 0..1", level)};
    out.battery = static_cast<float>(level);
  }
  out.state = text;
  out.offline = text == "offline";
  return CodecStatus::ok();
}

}  // namespace slam::protocol
