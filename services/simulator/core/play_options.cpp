// The log player's flags (play_options.hpp).
#include "simulator/core/play_options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "protocol/topic.hpp"

namespace slam::sim {

namespace {

// Room for "-K" after an id, inside the protocol's 64 bytes.
constexpr size_t kMaxIdFromPath = 56;
constexpr int kMaxPieces = 100;

}  // namespace

void add_play_options(CLI::App& app, PlayOptions& o) {
  app.add_option("--play", o.logs,
                 "play a robot log (CARMEN .clf or .clf.gz, ROS 2 .mcap) to the broker as a v2 robot, then "
                 "exit; repeat for several robots at once (no simulation runs)");
  app.add_option("--play-robot-id", o.robot_ids,
                 "robot id of each --play log, in order (default: the log's file name)");
  app.add_option("--play-rate", o.rate,
                 "playback speed, x real time (0: as fast as allowed, 500 scans/s a robot)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  app.add_option("--play-beams", o.beams, "thin each scan to N evenly spaced beams (0: every beam)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  app.add_option("--play-max-range", o.max_range_m,
                 "readings at or beyond M metres are sent as no return (0: the sensor's maximum)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  app.add_option("--play-start", o.start_s, "start S seconds after the log's first scan")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();
  app.add_option("--play-end", o.end_s, "stop S seconds after the log's first scan (0: at its end)")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();
  app.add_option("--play-pieces", o.pieces,
                 "cut each log into K consecutive pieces played at once as K robots (ids ID-1..ID-K)")
      ->check(CLI::Range(1, kMaxPieces))
      ->capture_default_str();
  app.add_option("--play-scan-topic", o.scan_topic, "MCAP logs: the sensor_msgs/msg/LaserScan topic to play");
  app.add_option("--play-odom-topic", o.odom_topic,
                 "MCAP logs: the nav_msgs/msg/Odometry topic to pair it with");
}

std::string robot_id_from_path(const std::string& path) {
  std::string name = std::filesystem::path(path).filename().string();
  for (bool stripped = true; stripped;) {
    stripped = false;
    for (const char* ext : {".gz", ".clf", ".log", ".txt", ".mcap"}) {
      const std::string_view e(ext);
      if (name.size() > e.size() && name.ends_with(e)) {
        name.resize(name.size() - e.size());
        stripped = true;
      }
    }
  }
  for (char& c : name) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '-' || c == '_' || c == '.';
    if (!plain) c = '_';
  }
  if (name.size() > kMaxIdFromPath) name.resize(kMaxIdFromPath);
  return name.empty() || name == "." || name == ".." ? "log" : name;
}

Result<std::vector<std::string>> play_robot_ids(const PlayOptions& o) {
  if (!o.robot_ids.empty() && o.robot_ids.size() != o.logs.size())
    return Error{
        fmt::format("--play-robot-id is given {} times for {} --play logs: give one per log, or none",
                    o.robot_ids.size(), o.logs.size())};
  std::vector<std::string> ids;
  for (size_t i = 0; i < o.logs.size(); ++i)
    ids.push_back(o.robot_ids.empty() ? robot_id_from_path(o.logs[i]) : o.robot_ids[i]);
  std::set<std::string> seen;
  for (const std::string& id : ids) {
    // Pieces append "-K": check the longest id the player will use.
    const std::string longest = o.pieces > 1 ? fmt::format("{}-{}", id, o.pieces) : id;
    if (auto s = protocol::validate_robot_id(longest); !s)
      return Error{fmt::format("--play-robot-id: '{}' is not a valid robot id: {}", longest, s.detail())};
    if (!seen.insert(id).second)
      return Error{
          fmt::format("two --play logs would play as robot '{}': name them with --play-robot-id", id)};
  }
  return ids;
}

Status validate(const PlayOptions& o) {
  if (!o.enabled()) {
    if (!o.robot_ids.empty()) return Error{"--play-robot-id needs --play"};
    return {};
  }
  if (o.end_s != 0 && o.end_s <= o.start_s)
    return Error{fmt::format("--play-end {} is not after --play-start {}", o.end_s, o.start_s)};
  if (!std::isfinite(o.rate + o.max_range_m + o.start_s + o.end_s))
    return Error{"--play-rate, --play-max-range, --play-start and --play-end must be finite"};
  if (auto ids = play_robot_ids(o); !ids) return ids.status();
  return {};
}

}  // namespace slam::sim
