#pragma once
// A robot log's scans as the mapper receives them from the gateway: one observation per scan, either
// a v2 scan (the sensor's pose and heading in the odometry frame, every return as a hit, beams without
// one as misses at the range limit) or a legacy v1 message (a position in whole centimetres, at most
// 16 obstacle points, no heading). What eval_log plays; plain C++.
#include <span>
#include <vector>

#include "common/core/geometry.hpp"
#include "mapper/core/mapper.hpp"
#include "protocol/codec_types.hpp"
#include "simulator/robot_log/robot_log.hpp"

namespace slam::bench {

struct LogObservationOptions {
  int beams = 0;              // thin each scan to this many evenly spaced beams; 0: all
  double max_range_m = 30.0;  // returns beyond this become misses (free up to it)
  double free_range_m = protocol::CodecLimits{}.scan_free_range_m;  // misses end here at most (the gateway's)
  bool v1 = false;  // legacy messages: centimetre position, no heading, hits only (<= 16)
  std::string robot = "log";
};

struct LogObservations {
  std::vector<mapper::OwnedObservation> observations;  // arrival order; seq = scan index + 1
  std::vector<double> stamps_s;                        // each scan's robot stamp
  std::vector<Pose> sensor_odom;                       // each scan's sensor pose (odometry frame)
  std::vector<Pose> sensor_in_robot;                   // each scan's sensor mount
};

// The observations of `scans`. Their stamp_ns is the arrival clock: the robot's stamps made
// non-decreasing (a log's stamps may step back; a message cannot arrive before the one before it).
LogObservations log_observations(std::span<const robot_log::LaserScan> scans,
                                 const LogObservationOptions& options);

// The indices of `count` beams evenly spaced over `total` (all of them when count is 0 or >= total).
std::vector<size_t> thinned_beams(size_t total, int count);

}  // namespace slam::bench
