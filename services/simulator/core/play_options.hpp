#pragma once
// slam-simulator --play: the flags of the log player (recorded robot logs played to the broker as
// v2 robots), as a plain struct with defaults, their CLI11 binding and the checks single-flag
// ranges cannot make.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "common/core/result.hpp"

namespace slam::sim {

struct PlayOptions {
  std::vector<std::string> logs;       // CARMEN (.clf, .gz) or ROS 2 MCAP (.mcap) files; empty: no player
  std::vector<std::string> robot_ids;  // one per log, in order; empty: each log's file name
  double rate = 1.0;                   // x real time; 0: as fast as kFastPaceS allows
  int beams = 0;                       // thin each scan to this many evenly spaced beams; 0: all
  double max_range_m = 0;              // readings at or beyond this become "no return"; 0: the sensor's
  double start_s = 0;                  // seconds from the log's first scan
  double end_s = 0;                    // seconds from the log's first scan; 0: to the end
  int pieces = 1;                      // cut each log into this many robots played at once
  std::string scan_topic;              // MCAP: the LaserScan topic when there are several
  std::string odom_topic;              // MCAP: the Odometry topic when there are several

  bool enabled() const { return !logs.empty(); }
};

// Scans of one robot go out at most this often at --play-rate 0, so a broker (and the mapper behind
// the gateway) is not flooded: 500 scans per second per robot.
inline constexpr double kFastPaceS = 0.002;

void add_play_options(CLI::App& app, PlayOptions& options);

// The robot id of a log: its file name without directories and the extensions .gz, .clf, .log,
// .txt and .mcap, with characters a robot id must not hold (or that would need escaping) made '_'.
std::string robot_id_from_path(const std::string& path);

// The robot ids the logs play as (one per log, before pieces add "-1".."-K"); an error for a
// count that does not match the logs, an invalid id or the same id twice.
Result<std::vector<std::string>> play_robot_ids(const PlayOptions& options);

Status validate(const PlayOptions& options);

}  // namespace slam::sim
