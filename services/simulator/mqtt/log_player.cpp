// The log player's loop (log_player.hpp).
#include "simulator/mqtt/log_player.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "common/core/shutdown.hpp"
#include "simulator/core/play_schedule.hpp"
#include "simulator/mqtt/robot_link.hpp"
#include "simulator/robot_log/read_robot_log.hpp"

namespace slam::sim {

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kProgressPeriodS = 2.0;
constexpr auto kMaxSleep = std::chrono::milliseconds(50);  // shutdown and progress stay responsive
constexpr double kConnectNoticeS = 5.0;

double percent(size_t part, size_t whole) {
  return whole == 0 ? 100.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// One robot being played: a piece and when each of its scans goes out.
struct Track {
  PlayPiece piece;
  std::vector<double> send_at;
  size_t next = 0;  // index into send_at
};

std::string stats_line(const std::string& path, const robot_log::LogStats& s) {
  std::string line = fmt::format("{}: {} scans, {} odometry, {} lines; {} bad lines, {} stamps back", path,
                                 s.scans, s.odometry, s.lines, s.bad_lines, s.stamps_back);
  if (s.stamp_jumps > 0) line += fmt::format(", {} stamp jumps (not waited out)", s.stamp_jumps);
  if (s.error_readings > 0) line += fmt::format(", {} error readings (left out)", s.error_readings);
  if (s.unknown_kinds > 0) line += fmt::format(", {} of kinds not played", s.unknown_kinds);
  if (!s.first_bad.empty()) line += fmt::format(" (first bad: {})", s.first_bad);
  return line;
}

RobotReport report_of(const std::string& robot_id, const PlayedScan& scan) {
  RobotReport r;
  r.robot_id = robot_id;
  // The robot's own clock. RobotLinks sends time_s as the v2 scan's "stamp" (the log's stamp hook).
  r.time_s = scan.stamp_s;
  r.reported_pose = scan.odom;
  r.true_pose = scan.odom;
  r.angles = scan.angles;
  r.ranges = scan.ranges;
  r.max_range = scan.max_range;
  r.sensor = scan.sensor;
  return r;
}

// Waits until every robot's connection is up (a real robot keeps trying too); false on shutdown.
bool wait_for_broker(RobotLinks& links, Counters& counters, size_t robots, const std::string& broker) {
  const auto t0 = Clock::now();
  double next_notice = kConnectNoticeS;
  for (;;) {
    links.poll(Clock::now());
    if (counters.get("mqtt_connected").load() >= static_cast<int64_t>(robots)) return true;
    if (seconds_since(t0) >= next_notice) {
      spdlog::info("play: waiting for the broker {} ({} of {} robots connected)", broker,
                   counters.get("mqtt_connected").load(), robots);
      next_notice += kConnectNoticeS;
    }
    if (wait_for_shutdown(std::chrono::milliseconds(20))) return false;
  }
}

}  // namespace

Status play_logs(const SimOptions& options, Counters& counters) {
  const PlayOptions& play = options.play;
  auto ids = play_robot_ids(play);
  if (!ids) return ids.error();
  robot_log::ReadOptions read;
  read.ros2.scan_topic = play.scan_topic;
  read.ros2.odom_topic = play.odom_topic;

  std::vector<robot_log::RobotLog> logs;
  std::vector<Track> tracks;
  size_t total = 0;
  for (size_t i = 0; i < play.logs.size(); ++i) {
    auto log = robot_log::read_robot_log(play.logs[i], read);
    if (!log) return Error{fmt::format("--play {}: {}", play.logs[i], log.message())};
    spdlog::info("play: {}", stats_line(play.logs[i], log->stats));
    auto pieces = plan_pieces(*log, i, (*ids)[i], play);
    if (!pieces) return Error{fmt::format("--play {}: {}", play.logs[i], pieces.message())};
    for (PlayPiece& p : *pieces) {
      Track t{std::move(p), {}, 0};
      t.send_at = send_times(*log, t.piece, play.rate);
      spdlog::info("play: robot '{}': scans {}..{} of {}, {:.1f} s of log", t.piece.robot_id, t.piece.first,
                   t.piece.end - 1, play.logs[i],
                   log->scans[t.piece.end - 1].stamp_s - log->scans[t.piece.first].stamp_s);
      total += t.piece.size();
      tracks.push_back(std::move(t));
    }
    logs.push_back(std::move(*log));
  }

  RobotLinks::Settings settings;
  settings.broker = options.broker;
  settings.protocol = RobotProtocol::V2;  // scans with heading and sensor offset need v2
  settings.multiplex = options.mqtt_multiplex;
  settings.limits = codec_limits(options);
  settings.password = options.mqtt_password;
  settings.tls_ca_file = options.tls_ca_file;
  auto links = RobotLinks::create(std::move(settings), counters);
  if (!links) return Error{"MQTT: " + links.message()};
  for (const Track& t : tracks)
    if (auto s = (*links)->add(t.piece.robot_id); !s) return Error{"MQTT: " + s.message()};
  if (!wait_for_broker(**links, counters, options.mqtt_multiplex ? 1 : tracks.size(), options.broker))
    return {};

  spdlog::info("play: {} scans as {} robots at {}", total, tracks.size(),
               play.rate > 0 ? fmt::format("{}x real time", play.rate) : std::string("full speed"));
  const auto t0 = Clock::now();
  double next_progress = kProgressPeriodS;
  size_t sent = 0;
  std::vector<WaypointOrder> orders;
  while (sent < total && !shutdown_requested()) {
    const double now = seconds_since(t0);
    double next_due = now + std::chrono::duration<double>(kMaxSleep).count();
    for (Track& t : tracks) {
      const auto& log = logs[t.piece.log];
      while (t.next < t.send_at.size() && t.send_at[t.next] <= now) {
        const PlayedScan scan = prepare_scan(log.scans[t.piece.first + t.next], play.beams, play.max_range_m);
        (*links)->publish(report_of(t.piece.robot_id, scan), true);
        ++t.next;
        ++sent;
      }
      if (t.next < t.send_at.size()) next_due = std::min(next_due, t.send_at[t.next]);
    }
    (*links)->poll(Clock::now());
    (*links)->drain_orders(orders);  // a log cannot follow waypoints: they are counted, then dropped
    if (now >= next_progress) {
      spdlog::info("play: {}/{} scans sent ({:.0f}%)", sent, total, percent(sent, total));
      next_progress += kProgressPeriodS;
    }
    const double wait_s = next_due - seconds_since(t0);
    if (wait_s > 0)
      wait_for_shutdown(std::chrono::milliseconds(static_cast<int64_t>(std::ceil(wait_s * 1e3))));
  }
  spdlog::info("play: {} {}/{} scans sent ({:.0f}%) in {:.1f} s; {} not sent (MQTT)",
               sent == total ? "done:" : "stopped:", sent, total, percent(sent, total), seconds_since(t0),
               counters.get("reports_dropped").load());
  return {};
}

}  // namespace slam::sim
