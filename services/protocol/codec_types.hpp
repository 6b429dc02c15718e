#pragma once
// What the codecs produce and the limits they enforce. Plain structs the service reuses message
// after message: clear() keeps vector and string capacity, so decoding stops allocating once warm.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/core/result.hpp"

namespace slam::protocol {

// Metres in the map frame (the frame robots report in).
struct Point {
  double x = 0.0;
  double y = 0.0;
  friend bool operator==(const Point&, const Point&) = default;
};

// One robot observation, ready to become a DDS RobotObservation.
struct DecodedObservation {
  // Ray-cast origin in the map frame: the robot position (v1, pose, points) or the sensor origin
  // (scan). theta is meaningful only when has_heading.
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  bool has_pose = false;  // false only for a v2 points message sent without a pose
  bool has_heading = false;
  // When the robot measured it, on the robot's own clock (v2 "stamp"); 0 when it sent none.
  std::int64_t robot_stamp_ns = 0;
  std::vector<Point> hits;    // obstacle points: ray end is occupied
  std::vector<Point> misses;  // beams that saw nothing up to max range: ray is free, end unknown
  // Scan beams with a range of 0: an error reading (a laser's "no measurement"), neither a hit at the
  // sensor nor free space; left out.
  std::uint32_t error_beams = 0;

  void clear() {
    x = y = theta = 0.0;
    has_pose = has_heading = false;
    robot_stamp_ns = 0;
    hits.clear();
    misses.clear();
    error_beams = 0;
  }
};

// A v2 status message, including the last-will {"state":"offline"}.
struct DecodedStatus {
  float battery = -1.0f;  // 0..1, negative when the message has none
  std::string state;      // 1..kMaxStateBytes bytes of clean UTF-8
  bool offline = false;   // state == "offline" (the last will)

  void clear() {
    battery = -1.0f;
    state.clear();
    offline = false;
  }
};

inline constexpr std::size_t kMaxRobotIdBytes = 64;  // IDL string<64>
inline constexpr std::size_t kMaxStateBytes = 32;    // IDL string<32>
// The largest v2 "stamp" in seconds: nanoseconds beyond it would not fit in the IDL's int64
// (9e9 s is the year 2255 as Unix time).
inline constexpr double kMaxRobotStampS = 9.0e9;

// Bounds on what a robot may send. Defaults suit indoor robots; validate() before use.
struct CodecLimits {
  double units_per_meter = 100.0;  // v1 robot units per metre (100: centimetres)
  std::size_t max_points = 4096;   // obstacle points (hits + misses) or beams per message
  std::size_t max_payload_bytes = 256 * 1024;
  double max_abs_coordinate_m = 10'000.0;  // any x or y, in metres
  double max_abs_angle_rad = 100.0;        // headings and beam angles need not be normalised
  // A scan's beam without a return clears free space this far at most (m): a real laser reads
  // nothing through glass and open doors, and free rays tens of metres long through a building's
  // gaps wore its walls away (the benchmark logs, docs/mapping-quality.md).
  double scan_free_range_m = 5.0;
};

// Rejects limits the codecs cannot work with, naming the key: "units_per_meter must be ...".
Status validate(const CodecLimits& limits);

}  // namespace slam::protocol
