#pragma once
// What the log player sends and when, as plain functions of a RobotLog and the --play flags: which
// scans (the --play-start/--play-end window, cut into --play-pieces consecutive pieces), when each
// goes out (the log's own spacing at --play-rate, never backwards), and how each is thinned and
// clipped (--play-beams, --play-max-range) into the beams of one v2 scan.
#include <string>
#include <vector>

#include "common/core/geometry.hpp"
#include "simulator/core/play_options.hpp"
#include "simulator/robot_log/robot_log.hpp"

namespace slam::sim {

// Consecutive scans of one log, played as one robot.
struct PlayPiece {
  std::string robot_id;
  size_t log = 0;    // index of the log in the player's list
  size_t first = 0;  // scans [first, end) of that log
  size_t end = 0;
  size_t size() const { return end - first; }
};

// The pieces of one log: the scans stamped within [start, end] seconds of its first scan (a
// contiguous run in file order), cut into `pieces` runs of equal count. One piece keeps
// `robot_id`; several are `robot_id`-1..-K. An error when the window holds fewer scans than pieces.
Result<std::vector<PlayPiece>> plan_pieces(const robot_log::RobotLog& log, size_t log_index,
                                           const std::string& robot_id, const PlayOptions& options);

// When each scan of a piece goes out, in seconds from the start of playback: the time since the
// piece's first stamp divided by `rate`, held when a stamp steps back (file order is kept), or
// one every kFastPaceS at rate 0. A step of more than robot_log::kStampJumpS either way (a clock
// set, a recording resumed hours later) is not waited out: the scan after it goes out right after
// the one before, and the time counts on from it.
std::vector<double> send_times(const robot_log::RobotLog& log, const PlayPiece& piece, double rate);

// A scan as it goes out: beams in the sensor frame, each range either a return (< max_range) or
// exactly max_range (no return, +inf included, as ROS writes it); beams with an error reading
// (<= 0 or NaN) are left out, since they say nothing about free space.
struct PlayedScan {
  double stamp_s = 0;  // robot clock
  Pose odom;           // robot pose in its odometry frame
  Pose sensor;         // laser mount in the robot frame
  std::vector<double> angles;
  std::vector<double> ranges;
  double max_range = 0;
};

// At most `beams` (0: all) evenly spaced beams, the centres of equal sectors of the scan's beams;
// readings at or beyond min(the scan's max range, `clip_m` when > 0) become no return.
PlayedScan prepare_scan(const robot_log::LaserScan& scan, int beams, double clip_m);

}  // namespace slam::sim
