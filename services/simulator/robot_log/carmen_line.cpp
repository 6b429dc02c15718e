// CARMEN log lines (carmen_line.hpp). Every field count is checked before a field is read, so a
// short, long or garbled line is an error naming what is wrong, never an out-of-range read.
#include "simulator/robot_log/carmen_line.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

namespace slam::robot_log {

namespace {

using Fields = std::vector<std::string_view>;

Fields split_fields(std::string_view line) {
  Fields fields;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
  return fields;
}

// A number filling the whole field; from_chars also reads "nan", "inf" and "-inf".
bool read_any_number(std::string_view field, double& out) {
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), out);
  return ec == std::errc{} && end == field.data() + field.size();
}

// A finite number filling the whole field.
bool read_number(std::string_view field, double& out) {
  return read_any_number(field, out) && std::isfinite(out);
}

bool read_count(std::string_view field, int64_t& out) {
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), out);
  return ec == std::errc{} && end == field.data() + field.size() && out >= 0;
}

// CARMEN's record kinds are upper-case words (FLASER, TRUEPOS, RAWLASER1, ...); anything else is junk.
bool is_kind_word(std::string_view field) {
  return std::all_of(field.begin(), field.end(),
                     [](char c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; });
}

Error bad(std::string_view kind, std::string_view why) {
  return Error{fmt::format("{}: {}", kind, why)};
}

// Reads fields[first, first + count) as finite numbers into out (resized).
Status read_numbers(const Fields& fields, size_t first, size_t count, std::string_view kind,
                    std::string_view what, std::vector<double>& out) {
  out.resize(count);
  for (size_t i = 0; i < count; ++i) {
    if (!read_number(fields[first + i], out[i]))
      return bad(kind, fmt::format("{} {} is not a finite number ('{:.20}')", what, i, fields[first + i]));
  }
  return Status::ok();
}

// Reads a scan's readings: numbers, but "nan" (an error reading) and "inf" (no return) as well, as
// a log converted from ROS writes them: one bad beam says nothing about the others.
Status read_readings(const Fields& fields, size_t first, size_t count, std::string_view kind,
                     std::vector<double>& out) {
  out.resize(count);
  for (size_t i = 0; i < count; ++i) {
    if (!read_any_number(fields[first + i], out[i]))
      return bad(kind, fmt::format("reading {} is not a number ('{:.20}')", i, fields[first + i]));
  }
  return Status::ok();
}

Pose pose_at(const std::vector<double>& v, size_t i) {
  return {v[i], v[i + 1], wrap_angle(v[i + 2])};
}

// Ranges as floats; a double beyond float's reach would be undefined to convert, and any such
// reading is "no return" (or, negative, an error reading) anyway. NaN stays NaN.
std::vector<float> to_ranges(const std::vector<double>& v) {
  std::vector<float> out(v.size());
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  for (size_t i = 0; i < v.size(); ++i) {
    out[i] = std::isnan(v[i]) ? std::numeric_limits<float>::quiet_NaN()
                              : static_cast<float>(std::clamp(v[i], -kFloatMax, kFloatMax));
  }
  return out;
}

// CARMEN's convention for lasers without angles: 180 degrees from -90; an odd count has a beam at
// each end (181: -90..+90), an even one not (180: -90..+89).
double flaser_increment(size_t beams) {
  if (beams < 2) return 0;
  return std::numbers::pi / static_cast<double>(beams % 2 == 0 ? beams : beams - 1);
}

// FLASER / RLASER n r1..rn x y theta odom_x odom_y odom_theta ipc_timestamp ipc_hostname logger_timestamp
Result<CarmenRecord> parse_flaser(const Fields& f, const CarmenContext& context, const CarmenOptions& options,
                                  bool rear) {
  const std::string_view kind = f[0];
  int64_t n = 0;
  if (f.size() < 2 || !read_count(f[1], n)) return bad(kind, "no reading count");
  const size_t beams = static_cast<size_t>(n);
  if (beams > f.size() || f.size() != beams + 11)
    return bad(kind, fmt::format("{} fields for {} readings, expected {}", f.size(), n, beams + 11));
  std::vector<double> ranges, tail;
  SLAM_TRY(read_readings(f, 2, beams, kind, ranges));
  SLAM_TRY(read_numbers(f, 2 + beams, 7, kind, "pose or stamp field", tail));
  double logger_stamp = 0;
  if (!read_number(f[beams + 10], logger_stamp)) return bad(kind, "logger_timestamp is not a finite number");
  LaserScan scan;
  scan.stamp_s = tail[6];
  scan.odom = pose_at(tail, 3);
  scan.laser_in_robot = rear ? Pose{context.rear_laser_offset_m, 0, std::numbers::pi}
                             : Pose{context.front_laser_offset_m, 0, 0};
  scan.angle_min_rad = -std::numbers::pi / 2;
  scan.angle_increment_rad = flaser_increment(beams);
  scan.max_range_m = options.flaser_max_range_m;
  scan.ranges = to_ranges(ranges);
  return CarmenRecord{CarmenKind::Scan, std::move(scan)};
}

// ROBOTLASER1 laser_type start_angle field_of_view angular_resolution maximum_range accuracy
// remission_mode n r1..rn m rem1..remm laser_x laser_y laser_theta robot_x robot_y robot_theta
// laser_tv laser_rv forward_safety_dist side_safety_dist turn_axis ipc_timestamp ipc_hostname
// logger_timestamp
Result<CarmenRecord> parse_robotlaser(const Fields& f) {
  const std::string_view kind = f[0];
  std::vector<double> head, ranges, remissions, tail;
  if (f.size() < 9) return bad(kind, fmt::format("{} fields, too few", f.size()));
  SLAM_TRY(read_numbers(f, 1, 7, kind, "header field", head));
  int64_t n = 0, m = 0;
  if (!read_count(f[8], n)) return bad(kind, "no reading count");
  const size_t beams = static_cast<size_t>(n);
  if (beams > f.size() || f.size() < beams + 10 || !read_count(f[9 + beams], m))
    return bad(kind, "no remission count after the readings");
  const size_t rems = static_cast<size_t>(m);
  if (rems > f.size() || f.size() != beams + rems + 24)
    return bad(kind, fmt::format("{} fields for {} readings and {} remissions, expected {}", f.size(), n, m,
                                 beams + rems + 24));
  SLAM_TRY(read_readings(f, 9, beams, kind, ranges));
  SLAM_TRY(read_numbers(f, 10 + beams, rems, kind, "remission", remissions));
  SLAM_TRY(read_numbers(f, 10 + beams + rems, 12, kind, "pose, velocity or stamp field", tail));
  double logger_stamp = 0;
  if (!read_number(f.back(), logger_stamp)) return bad(kind, "logger_timestamp is not a finite number");
  const double max_range = head[4];
  if (!(max_range > 0)) return bad(kind, "maximum_range is not positive");
  const Pose laser = pose_at(tail, 0), robot = pose_at(tail, 3);
  LaserScan scan;
  scan.stamp_s = tail[11];
  scan.odom = robot;
  scan.laser_in_robot = robot.inverse().compose(laser);
  scan.angle_min_rad = head[1];
  scan.angle_increment_rad = head[3];
  scan.max_range_m = max_range;
  scan.ranges = to_ranges(ranges);
  return CarmenRecord{CarmenKind::Scan, std::move(scan)};
}

// ODOM x y theta tv rv accel ipc_timestamp ipc_hostname logger_timestamp
Result<CarmenRecord> parse_odom(const Fields& f) {
  if (f.size() != 10) return bad(f[0], fmt::format("{} fields, expected 10", f.size()));
  std::vector<double> values;
  SLAM_TRY(read_numbers(f, 1, 7, f[0], "field", values));
  double logger_stamp = 0;
  if (!read_number(f[9], logger_stamp)) return bad(f[0], "logger_timestamp is not a finite number");
  return CarmenRecord{CarmenKind::Odometry, std::nullopt};
}

// PARAM name value [host stamp]
Result<CarmenRecord> parse_param(const Fields& f, CarmenContext& context) {
  if (f.size() < 3) return bad(f[0], "no name and value");
  double* offset = f[1] == "robot_frontlaser_offset"  ? &context.front_laser_offset_m
                   : f[1] == "robot_rearlaser_offset" ? &context.rear_laser_offset_m
                                                      : nullptr;
  if (offset != nullptr) {
    double value = 0;
    if (!read_number(f[2], value)) return bad(f[0], fmt::format("{} is not a finite number", f[1]));
    *offset = value;
  }
  return CarmenRecord{CarmenKind::Param, std::nullopt};
}

}  // namespace

Status CarmenOptions::validate() const {
  if (!(flaser_max_range_m > 0) || !std::isfinite(flaser_max_range_m))
    return Error{fmt::format("flaser_max_range_m must be finite and > 0, not {}", flaser_max_range_m)};
  return Status::ok();
}

Result<CarmenRecord> parse_carmen_line(std::string_view line, CarmenContext& context,
                                       const CarmenOptions& options) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  const Fields fields = split_fields(line);
  if (fields.empty() || fields[0].front() == '#') return CarmenRecord{};
  const std::string_view kind = fields[0];
  if (kind == "FLASER") return parse_flaser(fields, context, options, false);
  if (kind == "RLASER") return parse_flaser(fields, context, options, true);
  if (kind == "ROBOTLASER1") return parse_robotlaser(fields);
  if (kind == "ODOM") return parse_odom(fields);
  if (kind == "PARAM") return parse_param(fields, context);
  if (!is_kind_word(kind)) return Error{fmt::format("'{:.20}' is not a record kind", kind)};
  return CarmenRecord{CarmenKind::Unknown, std::nullopt};
}

}  // namespace slam::robot_log
