#pragma once
// The robot's half of v2 (what a v2 robot, or the simulator, sends): pose, polar scan and status
// as JSON text, with every field checked against the limits the gateway's decoders enforce (only a
// beam end point beyond max_abs_coordinate_m is left to the decoder). Numbers use the shortest form
// that reads back exactly.
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "protocol/codec_types.hpp"
#include "protocol/reject_reason.hpp"

namespace slam::protocol {

// v2/robot/<id>/pose: {"x":1.5,"y":-2,"heading":0.3}; heading omitted when absent.
struct V2Pose {
  double x = 0.0;
  double y = 0.0;
  std::optional<double> heading;
};

// Sensor mounting offset in the robot frame; the "sensor" member is written only when given.
struct V2SensorOffset {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
};

// v2/robot/<id>/scan. Beam i is at angle_min + i * angle_increment, unless `angles` is non-empty:
// then it lists every beam's angle (same length as ranges) and the start/step form is not written.
// A range >= max_range means "no return"; ranges are written as given.
struct V2Scan {
  V2Pose pose;  // heading required
  std::optional<V2SensorOffset> sensor;
  double angle_min = 0.0;
  double angle_increment = 0.0;
  std::span<const double> angles;
  std::span<const double> ranges;
  double max_range = 0.0;
  std::optional<double> stamp;  // "stamp": seconds on the robot's clock, written only when given
};

// v2/robot/<id>/status: {"battery":0.82,"state":"exploring"}; battery omitted when absent.
struct V2Status {
  std::string_view state;
  std::optional<double> battery;  // 0..1
};

// The last will a v2 robot registers on v2/robot/<id>/status.
inline constexpr std::string_view kV2OfflineStatus = R"({"state":"offline"})";

// Each replaces `out` (capacity kept) and leaves it empty on error. NonFinite for NaN/inf;
// OutOfRange for coordinates beyond max_abs_coordinate_m, angles beyond max_abs_angle_rad, a
// negative range, max_range <= 0 or battery outside 0..1; MissingField for a scan pose without
// heading; BadLength when angles and ranges differ in length; TooManyPoints beyond max_points;
// BadText for a state that is empty, longer than 32 bytes, or not clean UTF-8. A "stamp" (seconds
// on the robot's clock, written only when given) must be finite and within 0..kMaxRobotStampS.
CodecStatus encode_v2_pose(const V2Pose& pose, const CodecLimits& limits, std::string& out,
                           std::optional<double> stamp = std::nullopt);
CodecStatus encode_v2_scan(const V2Scan& scan, const CodecLimits& limits, std::string& out);
CodecStatus encode_v2_status(const V2Status& status, std::string& out);

}  // namespace slam::protocol
