// Start-up validation of codec limits: a bad value is a configuration error, reported by key.
#include "protocol/codec_types.hpp"

#include <cmath>
#include <string>

namespace slam::protocol {

Status validate(const CodecLimits& limits) {
  auto positive_finite = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive_finite(limits.units_per_meter))
    return Error{"units_per_meter must be a finite number > 0, got " +
                 std::to_string(limits.units_per_meter)};
  if (limits.max_points == 0) return Error{"max_points must be at least 1"};
  if (limits.max_payload_bytes < 4) return Error{"max_payload_bytes must be at least 4 (one v1 pair)"};
  if (!positive_finite(limits.max_abs_coordinate_m))
    return Error{"max_abs_coordinate_m must be a finite number > 0, got " +
                 std::to_string(limits.max_abs_coordinate_m)};
  if (!positive_finite(limits.scan_free_range_m))
    return Error{"scan_free_range_m must be a finite number > 0, got " +
                 std::to_string(limits.scan_free_range_m)};
  if (!positive_finite(limits.max_abs_angle_rad))
    return Error{"max_abs_angle_rad must be a finite number > 0, got " +
                 std::to_string(limits.max_abs_angle_rad)};
  return Status::ok();
}

}  // namespace slam::protocol
