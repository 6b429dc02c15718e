// v2 robot-side encoders. Written as text directly (no JSON document): the simulator sends one of
// these per robot per report, hundreds of robots at 10 Hz, so the warm path must not allocate.
#include "protocol/v2_robot_encode.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "protocol/text_check.hpp"

namespace slam::protocol {
namespace {

// The field name ("pose." + "x", "ranges" + "[3]") is only built for the error message.
CodecStatus fail(double v, const std::string& name, double bound) {
  if (!std::isfinite(v)) return {RejectReason::NonFinite, fmt::format("{} is {}", name, v)};
  return {RejectReason::OutOfRange, fmt::format("{} is {}, limit +/-{}", name, v, bound)};
}

bool fits(double v, double bound) {
  return std::isfinite(v) && std::abs(v) <= bound;
}

CodecStatus check(double v, std::string_view prefix, std::string_view name, double bound) {
  if (fits(v, bound)) return CodecStatus::ok();
  return fail(v, fmt::format("{}{}", prefix, name), bound);
}

CodecStatus check_indexed(double v, std::string_view base, std::size_t i, double bound) {
  if (fits(v, bound)) return CodecStatus::ok();
  return fail(v, fmt::format("{}[{}]", base, i), bound);
}

CodecStatus check_pose(const V2Pose& p, std::string_view where, const CodecLimits& limits) {
  const double c = limits.max_abs_coordinate_m;
  if (auto s = check(p.x, where, "x", c); !s) return s;
  if (auto s = check(p.y, where, "y", c); !s) return s;
  if (p.heading) return check(*p.heading, where, "heading", limits.max_abs_angle_rad);
  return CodecStatus::ok();
}

CodecStatus check_stamp(const std::optional<double>& stamp) {
  if (!stamp) return CodecStatus::ok();
  if (auto s = check(*stamp, "", "stamp", kMaxRobotStampS); !s) return s;
  if (*stamp < 0.0) return {RejectReason::OutOfRange, fmt::format("stamp is {}, must be >= 0", *stamp)};
  return CodecStatus::ok();
}

void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void append_member(std::string& out, std::string_view key, double value) {
  out += '"';
  out += key;
  out += "\":";
  append_number(out, value);
}

// The member `,"stamp":S` when the message has a stamp.
void append_stamp(std::string& out, const std::optional<double>& stamp) {
  if (!stamp) return;
  out += ',';
  append_member(out, "stamp", *stamp);
}

// x, y and heading, without braces: the pose message adds its stamp beside them.
void append_pose_members(std::string& out, const V2Pose& p) {
  append_member(out, "x", p.x);
  out += ',';
  append_member(out, "y", p.y);
  if (p.heading) {
    out += ',';
    append_member(out, "heading", *p.heading);
  }
}

void append_pose(std::string& out, const V2Pose& p) {
  out += '{';
  append_pose_members(out, p);
  out += '}';
}

void append_array(std::string& out, std::span<const double> values) {
  out += '[';
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) out += ',';
    append_number(out, values[i]);
  }
  out += ']';
}

CodecStatus check_scan(const V2Scan& scan, const CodecLimits& limits) {
  if (!scan.pose.heading)
    return {RejectReason::MissingField, "pose.heading is missing (a scan needs the heading)"};
  if (auto s = check_pose(scan.pose, "pose.", limits); !s) return s;
  const double c = limits.max_abs_coordinate_m;
  const double a = limits.max_abs_angle_rad;
  if (scan.sensor) {
    if (auto s = check(scan.sensor->x, "sensor.", "x", c); !s) return s;
    if (auto s = check(scan.sensor->y, "sensor.", "y", c); !s) return s;
    if (auto s = check(scan.sensor->theta, "sensor.", "theta", a); !s) return s;
  }
  if (auto s = check(scan.max_range, "", "max_range", c); !s) return s;
  if (scan.max_range <= 0.0)
    return {RejectReason::OutOfRange, fmt::format("max_range is {}, must be > 0", scan.max_range)};
  if (scan.ranges.size() > limits.max_points)
    return {RejectReason::TooManyPoints,
            fmt::format("ranges has {} entries, limit {}", scan.ranges.size(), limits.max_points)};
  if (scan.angles.empty()) {
    if (auto s = check(scan.angle_min, "", "angle_min", a); !s) return s;
    if (auto s = check(scan.angle_increment, "", "angle_increment", a); !s) return s;
  } else if (scan.angles.size() != scan.ranges.size()) {
    return {RejectReason::BadLength,
            fmt::format("angles has {} entries but ranges has {}", scan.angles.size(), scan.ranges.size())};
  }
  for (std::size_t i = 0; i < scan.angles.size(); ++i)
    if (auto s = check_indexed(scan.angles[i], "angles", i, a); !s) return s;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    if (auto s = check_indexed(scan.ranges[i], "ranges", i, c); !s) return s;
    if (scan.ranges[i] < 0.0)
      return {RejectReason::OutOfRange, fmt::format("ranges[{}] is {}, must be >= 0", i, scan.ranges[i])};
  }
  return check_stamp(scan.stamp);
}

}  // namespace

CodecStatus encode_v2_pose(const V2Pose& pose, const CodecLimits& limits, std::string& out,
                           std::optional<double> stamp) {
  out.clear();
  if (auto s = check_pose(pose, "", limits); !s) return s;
  if (auto s = check_stamp(stamp); !s) return s;
  out += '{';
  append_pose_members(out, pose);
  append_stamp(out, stamp);
  out += '}';
  return CodecStatus::ok();
}

CodecStatus encode_v2_scan(const V2Scan& scan, const CodecLimits& limits, std::string& out) {
  out.clear();
  if (auto s = check_scan(scan, limits); !s) return s;
  out += "{\"pose\":";
  append_pose(out, scan.pose);
  if (scan.sensor) {
    out += ",\"sensor\":{";
    append_member(out, "x", scan.sensor->x);
    out += ',';
    append_member(out, "y", scan.sensor->y);
    out += ',';
    append_member(out, "theta", scan.sensor->theta);
    out += '}';
  }
  if (scan.angles.empty()) {
    out += ',';
    append_member(out, "angle_min", scan.angle_min);
    out += ',';
    append_member(out, "angle_increment", scan.angle_increment);
  } else {
    out += ",\"angles\":";
    append_array(out, scan.angles);
  }
  out += ",\"ranges\":";
  append_array(out, scan.ranges);
  out += ',';
  append_member(out, "max_range", scan.max_range);
  append_stamp(out, scan.stamp);
  out += '}';
  return CodecStatus::ok();
}

CodecStatus encode_v2_status(const V2Status& status, std::string& out) {
  out.clear();
  if (status.state.empty()) return {RejectReason::BadText, "state is empty"};
  if (status.state.size() > kMaxStateBytes)
    return {RejectReason::BadText,
            fmt::format("state is {} bytes, limit {}", status.state.size(), kMaxStateBytes)};
  if (const auto problem = find_text_problem(status.state))
    return {RejectReason::BadText, fmt::format("state has {} at byte {}", problem->what, problem->offset)};
  if (status.battery) {
    if (auto s = check(*status.battery, "", "battery", 1.0); !s) return s;
    if (*status.battery < 0.0)
      return {RejectReason::OutOfRange, fmt::format("battery is {}, must be in 0..1", *status.battery)};
  }
  out += '{';
  if (status.battery) {
    append_member(out, "battery", *status.battery);
    out += ',';
  }
  out += "\"state\":\"";
  // Clean UTF-8 without control characters needs only the two JSON string escapes.
  for (const char ch : status.state) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  out += "\"}";
  return CodecStatus::ok();
}

}  // namespace slam::protocol
