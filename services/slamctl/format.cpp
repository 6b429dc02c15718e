#include "slamctl/format.hpp"

#include <array>
#include <cstdio>
#include <numbers>
#include <utility>

namespace slam::ctl {
namespace {

constexpr std::array<std::pair<std::string_view, GoalMode>, 7> kModes{{
    {"idle", GOAL_IDLE},
    {"direct", GOAL_DIRECT},
    {"planned", GOAL_PLANNED},
    {"square", GOAL_SQUARE},
    {"explore", GOAL_EXPLORE},
    {"home", GOAL_HOME},
    {"stop", GOAL_STOP},
}};

std::string fmt(const char* f, auto... args) {
  char buf[512];
  std::snprintf(buf, sizeof buf, f, args...);
  return buf;
}

std::string point(const Point2& p) {
  return fmt("(%.2f, %.2f)", p.x(), p.y());
}

double degrees(double radians) {
  return radians * 180.0 / std::numbers::pi;
}

// "(x, y, theta deg)"
std::string pose_deg(const Pose2& p) {
  return fmt("(%.2f, %.2f, %.1f deg)", p.x(), p.y(), degrees(p.theta()));
}

}  // namespace

std::optional<GoalMode> parse_goal_mode(std::string_view name) {
  for (const auto& [n, mode] : kModes)
    if (n == name) return mode;
  return std::nullopt;
}

std::string goal_mode_name(GoalMode mode) {
  for (const auto& [n, m] : kModes)
    if (m == mode) return std::string(n);
  return "mode " + std::to_string(static_cast<int>(mode));
}

std::string goal_status_name(GoalStatus status) {
  switch (status) {
    case GOAL_STATUS_NONE:
      return "none";
    case GOAL_STATUS_ACTIVE:
      return "active";
    case GOAL_STATUS_REACHED:
      return "reached";
    case GOAL_STATUS_FAILED:
      return "failed";
  }
  return "status " + std::to_string(static_cast<int>(status));
}

std::string plan_status_name(PlanStatus status) {
  switch (status) {
    case PLAN_OK:
      return "OK";
    case PLAN_START_BLOCKED:
      return "START_BLOCKED";
    case PLAN_GOAL_BLOCKED:
      return "GOAL_BLOCKED";
    case PLAN_NO_PATH:
      return "NO_PATH";
    case PLAN_TIMEOUT:
      return "TIMEOUT";
    case PLAN_NO_MAP:
      return "NO_MAP";
    case PLAN_INVALID_REQUEST:
      return "INVALID_REQUEST";
  }
  return "status " + std::to_string(static_cast<int>(status));
}

std::string map_result_name(MapResult result) {
  switch (result) {
    case MAP_OK:
      return "OK";
    case MAP_INVALID_REQUEST:
      return "INVALID_REQUEST";
    case MAP_IO_ERROR:
      return "IO_ERROR";
    case MAP_BAD_FILE:
      return "BAD_FILE";
    case MAP_UNKNOWN_ROBOT:
      return "UNKNOWN_ROBOT";
  }
  return "result " + std::to_string(static_cast<int>(result));
}

std::string correction_source_name(CorrectionSource source) {
  switch (source) {
    case CORRECTION_IDENTITY:
      return "identity";
    case CORRECTION_MATCH:
      return "match";
    case CORRECTION_LOOP:
      return "loop";
    case CORRECTION_OPERATOR:
      return "operator";
    case CORRECTION_RESTORED:
      return "restored";
  }
  return "source " + std::to_string(static_cast<int>(source));
}

double age_s(int64_t stamp_ns, int64_t now_ns) {
  return static_cast<double>(now_ns - stamp_ns) * 1e-9;
}

std::string format_heartbeat(const Heartbeat& hb, int64_t now_ns) {
  static constexpr const char* kStates[] = {"starting", "running", "stopping"};
  const auto state = static_cast<size_t>(hb.state());
  std::string out = fmt("%-10s %-24s pid %-7u up %8.1f s  %-8s  seen %.1f s ago\n", hb.service().c_str(),
                        hb.instance_id().c_str(), hb.pid(), hb.uptime_s(), state < 3 ? kStates[state] : "?",
                        age_s(hb.stamp_ns(), now_ns));
  for (const auto& c : hb.counters())
    out += fmt("    %-32s %lld\n", c.name().c_str(), static_cast<long long>(c.value()));
  return out;
}

std::string format_correction(const PoseCorrection& c) {
  return fmt("%s version %llu keyframes %u loops %u %s", pose_deg(c.map_from_odom()).c_str(),
             static_cast<unsigned long long>(c.version()), c.keyframes(), c.loop_closures(),
             correction_source_name(c.source()).c_str());
}

std::string format_robot(const RobotState& s, const PoseCorrection* correction, const RobotPath* path,
                         int64_t now_ns) {
  std::string mode = path ? goal_mode_name(path->mode()) + "/" + goal_status_name(path->status()) : "-";
  const std::string corrected = correction ? format_correction(*correction) : "-";
  return fmt(
      "%-16s %-7s %-3s x %8.2f  y %8.2f  %s  seen %6.1f s ago  msgs %llu  pts %llu  rejected %llu  %s  "
      "correction %s\n",
      s.robot_id().c_str(), s.presence() == PRESENCE_ONLINE ? "online" : "offline",
      s.protocol() == PROTOCOL_V1 ? "v1" : "v2", s.pose().x(), s.pose().y(),
      s.has_heading() ? fmt("th %6.2f", s.pose().theta()).c_str() : "th      -",
      age_s(s.last_seen_ns(), now_ns), static_cast<unsigned long long>(s.messages()),
      static_cast<unsigned long long>(s.points()), static_cast<unsigned long long>(s.rejected()),
      mode.c_str(), corrected.c_str());
}

std::string format_path_reply(const PathReply& r) {
  std::string out =
      fmt("%s  length %.2f m  %zu points  planned in %.1f ms", plan_status_name(r.status()).c_str(),
          r.length_m(), r.path().size(), r.planning_time_s() * 1e3);
  if (r.reason().size() > 0) out += std::string("  (") + r.reason().c_str() + ")";
  out += "\n";
  for (const auto& p : r.path()) out += "  " + point(p) + "\n";
  return out;
}

std::string describe(const RobotObservation& s) {
  return fmt("observation %s seq %llu pose (%.2f, %.2f, %s) hits %zu misses %zu", s.robot_id().c_str(),
             static_cast<unsigned long long>(s.seq()), s.pose().x(), s.pose().y(),
             s.has_heading() ? fmt("%.2f", s.pose().theta()).c_str() : "-", s.hits().size(),
             s.misses().size());
}
std::string describe(const RobotState& s) {
  return "state " + format_robot(s, nullptr, nullptr, s.last_seen_ns());
}
std::string describe(const RobotOdometry& s) {
  return fmt("odometry %s (%.2f, %.2f, %s) correction version %llu", s.robot_id().c_str(), s.odom_pose().x(),
             s.odom_pose().y(), s.has_heading() ? fmt("%.2f", s.odom_pose().theta()).c_str() : "-",
             static_cast<unsigned long long>(s.correction_version()));
}
std::string describe(const PoseCorrection& s) {
  return "correction " + s.robot_id().to_string() + " " + format_correction(s);
}
std::string describe(const InitialPose& s) {
  return fmt("initial pose %llu %s %s", static_cast<unsigned long long>(s.request_id()), s.robot_id().c_str(),
             pose_deg(s.pose()).c_str());
}
std::string describe(const GridSnapshot& s) {
  return fmt("snapshot layout %u version %llu %ux%u cells at %.3f m, origin (%.2f, %.2f), inflation %.2f m",
             s.layout_id(), static_cast<unsigned long long>(s.version()), s.info().width(), s.info().height(),
             s.info().resolution(), s.info().origin().x(), s.info().origin().y(),
             s.info().inflation_radius());
}
std::string describe(const GridTiles& s) {
  return fmt("patch layout %u version %llu %zu tiles of %u cells, %zu octets %s", s.layout_id(),
             static_cast<unsigned long long>(s.version()), s.tiles().size(), s.tile_side(), s.data().size(),
             s.encoding() == 0 ? "raw" : (s.encoding() == 1 ? "run-length" : "unknown encoding"));
}
std::string describe(const RobotPath& s) {
  return fmt("path %s goal %llu %s/%s target %s waypoint %u of %zu %s", s.robot_id().c_str(),
             static_cast<unsigned long long>(s.goal_id()), goal_mode_name(s.mode()).c_str(),
             goal_status_name(s.status()).c_str(), point(s.target()).c_str(), s.current(),
             s.waypoints().size(), s.reason().c_str());
}
std::string describe(const WaypointCommand& s) {
  return fmt("waypoint %s seq %llu %s (%zu more)", s.robot_id().c_str(),
             static_cast<unsigned long long>(s.seq()), point(s.waypoint()).c_str(), s.remaining().size());
}
std::string describe(const NavGoal& s) {
  return fmt("goal %s id %llu %s target %s", s.robot_id().c_str(),
             static_cast<unsigned long long>(s.goal_id()), goal_mode_name(s.mode()).c_str(),
             point(s.target()).c_str());
}
std::string describe(const MqttTraffic& s) {
  std::string hex;
  for (size_t i = 0; i < s.payload().size() && i < 16; ++i) hex += fmt("%02x", s.payload()[i]);
  return fmt("mqtt %s %s %u bytes %s%s", s.direction() == MQTT_INBOUND ? "in " : "out", s.topic().c_str(),
             s.payload_size(), hex.c_str(), s.payload_size() > 16 ? "..." : "");
}
std::string describe(const SimGroundTruth& s) {
  std::string out = fmt("ground truth %zu robots%s", s.robots().size(), s.paused() ? " (paused)" : "");
  for (const auto& r : s.robots())
    out += fmt("  %s (%.2f, %.2f)", r.robot_id().c_str(), r.true_pose().x(), r.true_pose().y());
  return out;
}
std::string describe(const Heartbeat& s) {
  return fmt("heartbeat %s %s up %.1f s, %zu counters", s.service().c_str(), s.instance_id().c_str(),
             s.uptime_s(), s.counters().size());
}
std::string describe(const MapReply& s) {
  return fmt("map reply %llu %s %s", static_cast<unsigned long long>(s.request_id()),
             map_result_name(s.result()).c_str(), s.message().c_str());
}
std::string describe(const PathReply& s) {
  return fmt("path reply %llu %s", static_cast<unsigned long long>(s.request_id()),
             format_path_reply(s).c_str());
}

}  // namespace slam::ctl
